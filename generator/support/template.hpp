// rotgen — filling @placeholder@ templates: the header skeletons in templates/*.in and the
// work-precision driver bench/workprecision/driver.cpp.in.
#pragma once

#include <map>
#include <string>

namespace rotgen {

enum class placeholders {
    all_required, // every @name@ must have a value (templates/*.in): a missing one is a logic_error
    known_only,   // only @name@ with a value is replaced; other '@' text stays as it is
};

// `text` with each @name@ replaced by values[name]. `name` labels the template in errors.
std::string fill_placeholders(const std::string& text,
                              const std::map<std::string, std::string>& values,
                              const std::string& name,
                              placeholders mode = placeholders::all_required);

} // namespace rotgen
