"""Mitsuba 3 plugins that implement ../shared/spec/conventions.md on Mitsuba's own ray casting.

`tracer_phong` is the Phong material (ambient, diffuse, specular, mirror) and `tracer_whitted`
the Whitted integrator. Neither is a Mitsuba built-in: `register()` must run before a scene
that names them is loaded (xcheck.mitsuba_render does it).
"""

import math

import drjit as dr
import mitsuba as mi
import numpy as np

from . import PHONG_PLUGIN, WHITTED_PLUGIN


def _color(props, name):
    """A colour property written as <rgb name=.../> (the converter writes every colour so)."""
    value = props.get(name)
    return mi.Color3f(value[0], value[1], value[2])


def _paint(props, name):
    """ka or kd: a colour, or a nested Mitsuba texture (checkerboard, bitmap) for a pattern."""
    value = props.get(name)
    return value if isinstance(value, mi.Texture) else mi.Color3f(value[0], value[1], value[2])


def _paint_at(paint, si, active):
    """A colour, or a texture's colour at the interaction (its uv)."""
    return paint.eval(si, active) if isinstance(paint, mi.Texture) else paint


class PhongBSDF(mi.BSDF):
    """Phong, not Blinn-Phong: eval = kd max(0, N.L) + ks max(0, R.V)^n with the normal turned
    to face the viewer; sample = the mirror direction with weight km; attribute "ka"."""

    def __init__(self, props) -> None:
        mi.BSDF.__init__(self, props)
        self.ka = _paint(props, "ka")
        self.kd = _paint(props, "kd")
        self.ks = _color(props, "ks")
        self.km = _color(props, "km")
        self.kt = _color(props, "kt") if "kt" in props else mi.Color3f(0.0)
        self.ior = mi.Float(props.get("ior", 1.0))
        self.n = mi.Float(props.get("n"))
        two_sided = mi.BSDFFlags.FrontSide | mi.BSDFFlags.BackSide
        self.m_components = [
            mi.BSDFFlags.DiffuseReflection | two_sided,
            mi.BSDFFlags.GlossyReflection | two_sided,
            mi.BSDFFlags.DeltaReflection | two_sided,
        ]
        self.m_flags = self.m_components[0] | self.m_components[1] | self.m_components[2]

    def eval(self, ctx, si, wo, active=True):
        # In the local shading frame N = (0, 0, 1); flipping z turns N towards the viewer (wi).
        side = dr.select(si.wi.z < 0, -1.0, 1.0)
        n_dot_l = wo.z * side
        r_dot_v = -wo.x * si.wi.x - wo.y * si.wi.y + n_dot_l * si.wi.z * side  # R = 2(N.L)N - L
        diffuse = _paint_at(self.kd, si, active) * dr.maximum(n_dot_l, 0.0)
        specular = self.ks * dr.power(dr.maximum(r_dot_v, 0.0), self.n)
        return dr.select(active, diffuse + specular, 0.0)

    def sample(self, ctx, si, sample1, sample2, active=True):
        bs = dr.zeros(mi.BSDFSample3f)
        bs.wo = mi.Vector3f(-si.wi.x, -si.wi.y, si.wi.z)  # mirror about N (either side)
        bs.pdf = mi.Float(1.0)
        bs.eta = mi.Float(1.0)
        bs.sampled_type = mi.UInt32(+mi.BSDFFlags.DeltaReflection)
        bs.sampled_component = mi.UInt32(2)
        return bs, dr.select(active, mi.Color3f(self.km), 0.0)

    def pdf(self, ctx, si, wo, active=True):
        return mi.Float(0.0)

    def eval_pdf(self, ctx, si, wo, active=True):
        return self.eval(ctx, si, wo, active), mi.Float(0.0)

    def has_attribute(self, name, active=True):
        return name in ("ka", "kt", "ior")

    def eval_attribute_3(self, name, si, active=True):
        # "ior" comes as a colour of three equal channels (attributes are colours or floats).
        values = {"ka": self.ka, "kt": self.kt, "ior": mi.Color3f(self.ior)}
        if name not in values:
            raise ValueError(f"{PHONG_PLUGIN} has no attribute '{name}'")
        if name == "ka":
            return dr.select(active, mi.Color3f(_paint_at(self.ka, si, active)), 0.0)
        return dr.select(active, mi.Color3f(values[name]), 0.0)

    def traverse(self, callback) -> None:
        pass

    def to_string(self) -> str:
        return f"PhongBSDF[ka={self.ka}, kd={self.kd}, ks={self.ks}, km={self.km}, kt={self.kt}, n={self.n}]"


# tracer's spawn rule (docs/robustness.md) in float32: a ray leaving a surface starts off it
# along the geometric normal, on the side it leaves, by a bound relative to the point's
# magnitude; a shadow ray stops SHADOW_EPSILON of the way short of its light. The bound is 64
# float32 ulps of (1 + max |p|): Mitsuba's own spawn_ray moves by 1500 (RayEpsilon), about 1e-3
# at task2's scale, and darkens floor pixels next to where a sphere touches it.
SPAWN_OFFSET = 2.0**-18
SHADOW_EPSILON = 1e-4


def _offset_origin(si, direction):
    n = mi.Vector3f(si.n)
    offset = SPAWN_OFFSET * (1.0 + dr.max(dr.abs(si.p)))
    side = dr.select(dr.dot(n, direction) < 0.0, -1.0, 1.0)
    return si.p + n * (side * offset)


def _spawn_ray(si, direction):
    return mi.Ray3f(_offset_origin(si, direction), direction)


def _spawn_ray_to(si, target):
    origin = _offset_origin(si, target - si.p)
    to_target = target - origin
    distance = dr.norm(to_target)
    ray = mi.Ray3f(origin, to_target / distance)
    ray.maxt = distance * (1.0 - SHADOW_EPSILON)
    return ray


# tracer's rule for refracted branches (src/render/whitted.cpp): dropped under this weight.
SMALLEST_BRANCH_WEIGHT = 1.0 / 4096


def _refracted(direction, normal, eta):
    """Snell's law for a unit direction and a unit normal facing it, eta = n_from / n_to:
    (refracted direction, total internal reflection mask)."""
    cos_in = -dr.dot(direction, normal)
    sin2_out = eta * eta * dr.maximum(0.0, 1.0 - cos_in * cos_in)
    tir = sin2_out > 1.0
    out = eta * direction + (eta * cos_in - dr.sqrt(dr.maximum(0.0, 1.0 - sin2_out))) * normal
    return dr.normalize(out), tir


class _PinholeCamera:
    """tracer's camera (src/render/camera.cpp) in float64, from the converter's numbers: eye,
    lookat, up, fovy, width, height, sample grid side."""

    def __init__(self, text) -> None:
        numbers = [float(x) for x in text.split()]
        eye, lookat, up = numbers[0:3], numbers[3:6], numbers[6:9]
        fovy, self.width, self.height, self.grid = numbers[9:13]

        def unit(v):
            inverse = 1.0 / math.sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2])
            return [x * inverse for x in v]

        def cross(a, b):
            return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]

        w = unit([a - b for a, b in zip(eye, lookat, strict=True)])
        u = unit(cross(up, w))
        v = cross(w, u)
        plane_height = 2.0 * math.tan(fovy * 0.017453292519943295 / 2.0)
        plane_width = plane_height * self.width / self.height
        self.eye = eye
        self.basis = u, v, w
        self.plane = plane_width, plane_height
        self.step_x = [x * (plane_width / self.width) for x in u]
        self.step_y = [-x * (plane_height / self.height) for x in v]
        self.corner = [-0.5 * plane_width * a + 0.5 * plane_height * b - c for a, b, c in zip(u, v, w, strict=True)]

    def exact_ray(self, ray):
        """(origin, direction) in float64 of tracer's ray through the sample point nearest to
        where Mitsuba's float32 ray goes: the centre of a cell of the pixel's grid."""
        u, v, w = (mi.Vector3d(*axis) for axis in self.basis)
        d = mi.Vector3d(ray.d)
        depth = -dr.dot(d, w)
        x = (dr.dot(d, u) / depth / self.plane[0] + 0.5) * self.width
        y = (0.5 - dr.dot(d, v) / depth / self.plane[1]) * self.height
        px = (dr.floor(x * self.grid) + 0.5) / self.grid
        py = (dr.floor(y * self.grid) + 0.5) / self.grid
        corner, step_x, step_y = mi.Vector3d(*self.corner), mi.Vector3d(*self.step_x), mi.Vector3d(*self.step_y)
        direction = dr.normalize((corner + px * step_x) + py * step_y)
        return mi.Point3d(*self.eye), direction


def _registry_id(shape):
    """The number Mitsuba gives a shape in its registry: what a SurfaceInteraction's `shape`
    holds, used here to index per-shape tables."""
    return dr.reinterpret_array(mi.UInt32, mi.ShapePtr(shape))[0]


class WhittedIntegrator(mi.SamplingIntegrator):
    """Whitted recursion of conventions.md: colour = ka + sum over unblocked point lights of
    light colour * Phong (no fall-off) + km * trace(mirror ray) [+ kt * trace(refracted ray),
    tracer's refraction], for levels 0..max_depth; misses return the background; the level
    after max_depth returns black. Unrolled in Python: with `refracts` every level also opens
    a refracted path: up to 2^(max_depth + 1) path segments, each level's state evaluated first
    (a cold kernel cache took 271 s for scenes/glass.scn as one kernel, 11 s so)."""

    def __init__(self, props) -> None:
        mi.SamplingIntegrator.__init__(self, props)
        self.max_depth = props.get("max_depth", 4)
        self.shadows = props.get("shadows", True)
        self.refracts = props.get("refracts", False)
        self.background = _color(props, "background") if "background" in props else mi.Color3f(0.0)
        self.sphere_numbers = [float(x) for x in props.get("spheres", "").split()] if "spheres" in props else []
        self._sphere_table = None
        self._mesh_table = None  # set by use_exact_meshes
        self.camera = _PinholeCamera(props.get("camera")) if "camera" in props else None

    def sample(self, scene, sampler, ray, medium=None, active=True):
        ray = mi.Ray3f(ray)
        exact = self.camera.exact_ray(ray) if self.camera else None
        color = self._path(scene, ray, mi.Color3f(1.0), 0, mi.Bool(active), exact)
        return color, mi.Bool(True), []

    def _spheres(self, scene):
        """The spheres in float64 by shape: (centre x, y, z, radius) arrays indexed by a shape's
        registry id (radius 0: not a sphere), built once from the converter's list."""
        if self._sphere_table is None:
            entries, size = {}, 1
            for shape in scene.shapes():
                registry_id = _registry_id(shape)
                size = max(size, registry_id + 1)  # every shape's id indexes the table
                name = shape.id()
                if name.startswith("sphere") and name[6:].isdigit() and 4 * int(name[6:]) < len(self.sphere_numbers):
                    entries[registry_id] = int(name[6:])
            columns = [[0.0] * size for _ in range(4)]
            for registry_id, index in entries.items():
                for k in range(4):
                    columns[k][registry_id] = self.sphere_numbers[4 * index + k]
            self._sphere_table = [mi.Float64(column) for column in columns]
        return self._sphere_table

    def use_exact_meshes(self, scene, shapes, corners, normals) -> None:
        """Takes the triangle meshes in float64 (xcheck.exact_meshes: by shape id, the first
        triangle, the count, to_object and translation; the corners and normals table): a
        mirror chain's hit on them is then solved again in float64 too. A shape whose triangle
        count or float32 corners differ from Mitsuba's is left out."""
        size = 1 + max(_registry_id(shape) for shape in scene.shapes())
        first, count = [0] * size, [0] * size
        maps = [[0.0] * size for _ in range(12)]
        for shape in scene.shapes():
            entry = shapes.get(shape.id())
            if entry is None or not shape.is_mesh() or shape.face_count() != entry[1]:
                continue
            start, triangles, to_object, translate = entry
            # The triangles in Mitsuba's order: its float32 corners agree with the placed ones.
            placed = np.einsum("ij,tkj->tki", np.linalg.inv(to_object), corners[start : start + triangles]) + translate
            ours = np.array(shape.vertex_positions_buffer(), dtype=np.float64).reshape(-1, 3)
            ours = ours[np.array(shape.faces_buffer(), dtype=np.int64).reshape(-1, 3)]
            if not np.allclose(ours, placed, rtol=0.0, atol=1e-5 * (1.0 + np.abs(placed).max())):
                continue
            registry_id = _registry_id(shape)
            first[registry_id], count[registry_id] = start, triangles
            for k, value in enumerate([*np.asarray(to_object).ravel(), *translate]):
                maps[k][registry_id] = float(value)
        if not any(count):  # no mesh taken (a scene of rectangles and spheres): nothing to gather from
            self._mesh_table = None
            return
        columns = [
            mi.Float64(np.ascontiguousarray(table.reshape(-1, 9)[:, k]))
            for table in (corners, normals)
            for k in range(9)
        ]
        self._mesh_table = (mi.UInt32(first), mi.UInt32(count), [mi.Float64(m) for m in maps], columns)

    def _refine(self, scene, si, ray, origin, direction, active):
        """The hit in float64: on a sphere, t solved again along the float64 ray (origin,
        direction) with the sphere's double centre and radius; on a triangle of an exact mesh
        (use_exact_meshes), with the triangle's double corners in the mesh's own coordinates;
        elsewhere Mitsuba's t along its own ray `ray` (a triangle's float32 corners put
        Mitsuba's interpolated point, and any plane through it, off by about 6e-8 of their
        distance from the origin: far over epsilon on the big outer triangles of the plane
        squares). (point, geometric normal, shading normal, solved in float64)."""
        table = self._spheres(scene)
        registry_id = dr.reinterpret_array(mi.UInt32, si.shape)
        centre = mi.Point3d(*(dr.gather(mi.Float64, table[k], registry_id, active) for k in range(3)))
        radius = dr.gather(mi.Float64, table[3], registry_id, active)
        # Haines' chord form of the discriminant; of the two roots the one nearer Mitsuba's own
        # t (a ray that starts on the sphere, inside it, has a root at about 0 too).
        f = origin - centre
        a = dr.dot(direction, direction)
        b = dr.dot(f, direction)
        chord = f - (b / a) * direction
        discriminant = a * (radius * radius - dr.dot(chord, chord))
        q = -(b + dr.copysign(dr.sqrt(dr.maximum(discriminant, 0.0)), b))
        t0, t1 = (dr.dot(f, f) - radius * radius) / q, q / a
        mitsuba_t = mi.Float64(si.t)
        t = dr.select(dr.abs(t0 - mitsuba_t) < dr.abs(t1 - mitsuba_t), t0, t1)
        on_sphere = (radius > 0.0) & (discriminant >= 0.0) & (t > 0.0)
        along_ray = mi.Point3d(ray.o) + mitsuba_t * mi.Vector3d(ray.d)
        point = dr.select(on_sphere, origin + t * direction, along_ray)
        geometric = dr.select(on_sphere, (point - centre) / radius, mi.Vector3d(si.n))
        shading = dr.select(on_sphere, geometric, mi.Vector3d(si.sh_frame.n))
        if self._mesh_table is None:
            return point, geometric, shading, on_sphere
        mesh_point, mesh_geometric, mesh_shading, on_mesh = self._mesh_hit(si, registry_id, origin, direction, active)
        point = dr.select(on_mesh, mesh_point, point)
        geometric = dr.select(on_mesh, mesh_geometric, geometric)
        shading = dr.select(on_mesh, mesh_shading, shading)
        return point, geometric, shading, on_sphere | on_mesh

    def _mesh_hit(self, si, registry_id, origin, direction, active):
        """The hit on the triangle Mitsuba met, in float64, as tracer finds it: the ray carried
        into the mesh's own coordinates, t and the barycentrics by Moller-Trumbore, the point
        along the float64 ray, the vertex normals mapped by transpose(to_object), normalised and
        interpolated (the face's normal where they cancel). (point, geometric normal, shading
        normal, found)."""
        first, count, maps, columns = self._mesh_table
        active = active & (dr.gather(mi.UInt32, count, registry_id, active) > 0)
        index = dr.gather(mi.UInt32, first, registry_id, active) + si.prim_index
        value = [dr.gather(mi.Float64, maps[k], registry_id, active) for k in range(12)]
        to_object = mi.Matrix3f64(*value[:9])
        translate = mi.Vector3d(*value[9:])
        corner = [
            mi.Point3d(*(dr.gather(mi.Float64, columns[3 * c + k], index, active) for k in range(3))) for c in range(3)
        ]
        normal = [
            mi.Vector3d(*(dr.gather(mi.Float64, columns[9 + 3 * c + k], index, active) for k in range(3)))
            for c in range(3)
        ]
        o = to_object @ (origin - translate)
        d = to_object @ direction
        e1, e2 = corner[1] - corner[0], corner[2] - corner[0]
        p = dr.cross(d, e2)
        det = dr.dot(e1, p)
        s = o - corner[0]
        qv = dr.cross(s, e1)
        u, v, t = dr.dot(s, p) / det, dr.dot(d, qv) / det, dr.dot(e2, qv) / det
        found = active & (det != 0.0) & (t > 0.0) & dr.isfinite(t)
        normal_map = to_object.T

        def unit_or_zero(x):
            length = dr.norm(x)
            return dr.select(length > 0.0, x / length, 0.0)

        geometric = unit_or_zero(normal_map @ dr.cross(e1, e2))
        mapped = [unit_or_zero(normal_map @ n) for n in normal]
        shading = unit_or_zero((1.0 - u - v) * mapped[0] + u * mapped[1] + v * mapped[2])
        shading = dr.select(dr.norm(shading) > 0.0, shading, geometric)
        found &= dr.norm(geometric) > 0.0
        return origin + t * direction, geometric, shading, found

    def _path(self, scene, ray, weight, first_depth, active, exact=None):
        """The colour along one path from level first_depth: hits shaded, mirror bounces
        followed; each refraction opens a path of its own (recursion, unrolled)."""
        color = mi.Color3f(0.0)
        ctx = mi.BSDFContext()
        # The mirror chain's ray in float64 (Mitsuba's own rays are float32): each ray leaves
        # the exact float64 point it starts from; Mitsuba only names the shape it meets next
        # (from an origin moved off the surface), and the hit is worked out again in float64.
        # Along a chain of mirror spheres float32 rounding would otherwise grow from bounce to
        # bounce (docs/crosscheck.md).
        origin, direction = exact if exact else (mi.Point3d(ray.o), mi.Vector3d(ray.d))
        for depth in range(first_depth, self.max_depth + 1):
            # The level's state in memory: each level's kernel then starts from it, the same
            # code at every branch (compiled once, not once per path prefix).
            dr.eval(ray, origin, direction, weight, active, color)
            # Step 1: the nearest surface, or the background.
            si = scene.ray_intersect(ray, active)
            missed = active & ~si.is_valid()
            color += dr.select(missed, weight * self.background, 0.0)
            active &= si.is_valid()
            bsdf = si.bsdf(ray)
            # The point along the float64 ray, as tracer has it: Mitsuba interpolates it from a
            # triangle's float32 corners, off by about 6e-8 of their distance from the origin:
            # far over epsilon on the big outer triangles of the plane squares.
            point, geometric, shading, _ = self._refine(scene, si, ray, origin, direction, active)
            si.p = mi.Point3f(point)

            # Step 2: ambient, then each light that the point sees.
            color += dr.select(active, weight * bsdf.eval_attribute_3("ka", si, active), 0.0)
            for emitter in scene.emitters():
                ds, spectrum = emitter.sample_direction(si, mi.Point2f(0.0), active)
                light_color = spectrum * dr.square(ds.dist)  # undo Mitsuba's 1/r^2 fall-off
                term = light_color * bsdf.eval(ctx, si, si.to_local(ds.d), active)
                lit = active & dr.any(term != 0.0)
                if self.shadows:
                    lit &= ~scene.ray_test(_spawn_ray_to(si, ds.p), lit)
                color += dr.select(lit, weight * term, 0.0)
            if depth == self.max_depth:
                break

            # Step 3: the refracted path (entering when the geometric normal faces the ray);
            # on total internal reflection kt joins km.
            bs, reflect = bsdf.sample(ctx, si, 0.0, mi.Point2f(0.0), active)
            if self.refracts:
                kt = bsdf.eval_attribute_3("kt", si, active)
                ior = bsdf.eval_attribute_3("ior", si, active).x
                entering = dr.dot(si.n, ray.d) < 0.0
                eta = dr.select(entering, 1.0 / ior, ior)
                shading = mi.Vector3f(si.sh_frame.n)
                normal = dr.select(dr.dot(shading, ray.d) > 0.0, -shading, shading)
                refracted, tir = _refracted(ray.d, normal, eta)
                transmits = active & dr.any(kt != 0.0)
                reflect += dr.select(transmits & tir, kt, 0.0)
                branch = weight * kt
                opens = transmits & ~tir & (dr.max(branch) >= SMALLEST_BRANCH_WEIGHT)
                if dr.any(opens):
                    color += self._path(scene, _spawn_ray(si, refracted), branch, depth + 1, opens)

            # Step 4: continue along the mirror direction (about the shading normal, in float64
            # on spheres and exact meshes), from the float64 point.
            weight *= dr.select(active, reflect, 0.0)
            active &= dr.any(weight != 0.0)
            direction = direction - 2.0 * dr.dot(direction, shading) * shading
            origin = point
            side = dr.select(dr.dot(geometric, direction) < 0.0, -1.0, 1.0)
            offset = SPAWN_OFFSET * (1.0 + dr.max(dr.abs(point)))
            ray = mi.Ray3f(mi.Point3f(point + geometric * (side * offset)), mi.Vector3f(direction))
        return color

    def aov_names(self):
        return []

    def to_string(self) -> str:
        return f"WhittedIntegrator[max_depth={self.max_depth}, shadows={self.shadows}, refracts={self.refracts}]"


def register() -> None:
    """Registers both plugins with the current Mitsuba variant (call after mi.set_variant)."""
    mi.register_bsdf(PHONG_PLUGIN, lambda props: PhongBSDF(props))
    mi.register_integrator(WHITTED_PLUGIN, lambda props: WhittedIntegrator(props))
