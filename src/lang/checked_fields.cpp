#include "lang/checked_fields.h"

#include <mutex>
#include <stdexcept>

#include "lang/interpreter.h"

namespace tracer {

const Value& default_of(const KeySpec& key) {
    static std::mutex mutex;
    static std::map<const KeySpec*, Value> cache;
    std::lock_guard lock(mutex);
    auto found = cache.find(&key);
    if (found != cache.end()) return found->second;
    SourceFile file("<default>", std::string(key.default_value));
    Diagnostics ignored;
    Value value;
    if (!evaluate_single_value(file, ignored, value)) std::abort();  // a broken table: a bug
    return cache.emplace(&key, std::move(value)).first->second;
}

const KeySpec& Fields::key(std::string_view name) const {
    const KeySpec* found = spec_->find_key(name);
    if (!found)
        throw std::logic_error("a builder asked for the key '" + std::string(name) + "', which the table of '" +
                               std::string(spec_->kind) + "' does not have");
    return *found;
}

const Fields& Fields::child(std::string_view name) const {
    auto found = children_.find(key(name).name);
    if (found == children_.end())
        throw std::logic_error("'" + std::string(name) + "' of '" + std::string(spec_->kind) +
                               "' is not a nested block, or was not checked");
    return *found->second;
}

}  // namespace tracer
