// The OBJ reader of io/: faces, indices, normals and the errors of bad files, on text made here
// (mesh_from_obj_text: what load_mesh does once it has read a file).
#include <gtest/gtest.h>

#include <set>
#include <string>

#include "io/obj_mesh.h"

namespace tracer {
namespace {

const std::string kSquare = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n";

TEST(ObjMesh, AQuadBecomesTwoTrianglesOverItsFourCorners) {
    Diagnostics diagnostics;
    const auto mesh = mesh_from_obj_text("square.obj", kSquare + "f 1 2 3 4\n", diagnostics);
    ASSERT_TRUE(mesh) << diagnostics.error_count();
    EXPECT_EQ(mesh->positions.size(), 4u);
    ASSERT_EQ(mesh->triangles.size(), 2u);
    std::set<uint32_t> corners;
    for (const auto& triangle : mesh->triangles) corners.insert(triangle.begin(), triangle.end());
    EXPECT_EQ(corners, (std::set<uint32_t>{0, 1, 2, 3}));
    EXPECT_TRUE(mesh->normals.empty());
    EXPECT_EQ(diagnostics.error_count(), 0);
}

TEST(ObjMesh, NegativeIndicesCountBackFromTheLastVertex) {
    Diagnostics diagnostics;
    const auto mesh = mesh_from_obj_text("relative.obj", kSquare + "f -4 -3 -2\n", diagnostics);
    ASSERT_TRUE(mesh);
    ASSERT_EQ(mesh->triangles.size(), 1u);
    EXPECT_EQ(mesh->triangles[0], (std::array<uint32_t, 3>{0, 1, 2}));
}

TEST(ObjMesh, FileNormalsAreKeptOnlyWhenEveryFaceHasThem) {
    const std::string normals = kSquare + "vn 0 0 2\n";
    Diagnostics all;
    const auto every = mesh_from_obj_text("n.obj", normals + "f 1//1 2//1 3//1\nf 1//1 3//1 4//1\n", all);
    ASSERT_TRUE(every);
    ASSERT_EQ(every->normal_ids.size(), 2u);
    EXPECT_EQ(every->normals.at(every->normal_ids[0][0]), glm::dvec3(0, 0, 2));  // as written, not normalised
    Diagnostics some;
    const auto mixed = mesh_from_obj_text("m.obj", normals + "f 1//1 2//1 3//1\nf 1 3 4\n", some);
    ASSERT_TRUE(mixed);
    EXPECT_EQ(mixed->triangles.size(), 2u);
    EXPECT_TRUE(mixed->normal_ids.empty());
}

TEST(ObjMesh, ZeroAreaTrianglesAreDroppedWithAWarning) {
    Diagnostics diagnostics;
    const auto mesh = mesh_from_obj_text("flat.obj", kSquare + "v 2 0 0\nf 1 2 3\nf 1 2 5\n", diagnostics);
    ASSERT_TRUE(mesh);
    EXPECT_EQ(mesh->triangles.size(), 1u);  // 1 2 5 lie on one line
    EXPECT_EQ(diagnostics.error_count(), 0);
    EXPECT_EQ(diagnostics.warning_count(), 1);
    EXPECT_NE(diagnostics.all().front().message.find("degenerate (zero-area) triangle dropped"), std::string::npos);
}

TEST(ObjMesh, AnIndexPastTheVerticesIsAnErrorAtItsLineAndColumn) {
    Diagnostics diagnostics;
    const auto mesh = mesh_from_obj_text("bad.obj", kSquare + "f 1 2 9\n", diagnostics);
    EXPECT_FALSE(mesh);
    ASSERT_EQ(diagnostics.error_count(), 1);
    const Diagnostic& error = diagnostics.all().front();
    EXPECT_EQ(error.location.path, "bad.obj");
    EXPECT_EQ(error.location.line, 5);
    EXPECT_EQ(error.location.column, 7);
}

TEST(ObjMesh, AFileWithoutFacesIsAnError) {
    Diagnostics diagnostics;
    EXPECT_FALSE(mesh_from_obj_text("empty.obj", kSquare, diagnostics));
    EXPECT_TRUE(diagnostics.has_errors());
}

TEST(ObjMesh, TextureCoordinatesAreKeptOnlyWhenEveryFaceHasThem) {
    const std::string square = kSquare + "vt 0 0\nvt 1 0\nvt 1 1\nvt 0.5\n";
    Diagnostics all;
    const auto every = mesh_from_obj_text("t.obj", square + "f 1/1 2/2 3/3\nf 1/1/ 3/3 4/4\n", all);
    ASSERT_TRUE(every);
    ASSERT_EQ(every->texcoord_ids.size(), 2u);
    EXPECT_EQ(every->texcoord_ids[1], (std::array<uint32_t, 3>{0, 2, 3}));
    EXPECT_EQ(every->texcoords[3], glm::dvec2(0.5, 0));  // a missing v is 0
    Diagnostics some;
    const auto partly = mesh_from_obj_text("t.obj", square + "f 1/1 2/2 3/3\nf 1 3 4\n", some);
    ASSERT_TRUE(partly);
    EXPECT_TRUE(partly->texcoord_ids.empty());
    EXPECT_TRUE(partly->texcoords.empty());
}

TEST(ObjMesh, BadTextureCoordinatesAreErrors) {
    for (const std::string& bad : {kSquare + "vt 0 0\nf 1/2 2/1 3/1\n", kSquare + "vt nan 0\nf 1/1 2/1 3/1\n",
                                   kSquare + "vt\nf 1 2 3\n", kSquare + "vt 0 0 0 0\nf 1 2 3\n"}) {
        Diagnostics diagnostics;
        EXPECT_FALSE(mesh_from_obj_text("bad.obj", bad, diagnostics)) << bad;
        EXPECT_GE(diagnostics.error_count(), 1) << bad;
    }
}

}  // namespace
}  // namespace tracer
