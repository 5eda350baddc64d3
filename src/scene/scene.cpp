#include "scene/scene.h"

namespace tracer {

const char* accelerator_name(Accelerator accelerator) {
    switch (accelerator) {
        case Accelerator::None:
            return "none";
        case Accelerator::Box:
            return "box";
        case Accelerator::Median:
            return "median";
        case Accelerator::Sah:
            return "sah";
    }
    return "sah";
}

bool accelerator_from_name(std::string_view name, Accelerator& out) {
    for (Accelerator a : {Accelerator::None, Accelerator::Box, Accelerator::Median, Accelerator::Sah})
        if (name == accelerator_name(a)) {
            out = a;
            return true;
        }
    return false;
}

}  // namespace tracer
