// rotgen — texts that stand for files: a caller holding a model or a scene in memory (the Python
// module's rotgen.Model(yaml_text=...) and rotgen.Scene(dict)) names it with a path that is no
// file (such as "<scene>"), and spec/'s load_yaml_file reads that path's text from here instead of
// from the disk. Errors then name that path, with the line and column in the text.
#pragma once

#include <string>

namespace rotgen {

// Registers `text` as the content of `path` (replacing any text registered before); thread-safe.
void set_memory_file(const std::string& path, const std::string& text);
// Forgets `path`: reading it goes to the disk again.
void erase_memory_file(const std::string& path);
// The registered text of `path` into `text`; false (and `text` untouched) when there is none.
bool memory_file(const std::string& path, std::string& text);

} // namespace rotgen
