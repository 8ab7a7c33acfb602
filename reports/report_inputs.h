// The report's inputs other than results files, checked before anything is written.
#pragma once

#include <optional>
#include <string>
#include <vector>

namespace sdb {

// The pictures manifest for a report into `out_dir` (interfaces: DIR/pictures/pictures.json,
// else pictures/pictures.json beside the first results file), or nullopt when there is none.
std::optional<std::string> find_pictures_manifest(const std::string& out_dir, const std::string& first_input);

// Throws InputError naming the manifest (or a picture it names) when it is not valid JSON, has
// another schema, lacks a field the report reads, or names a picture that is not a file inside
// its folder.
void check_pictures_manifest(const std::string& path);

// Throws InputError naming the file when a paper table cannot be read or is empty.
void check_paper_tables(const std::vector<std::string>& paths);

}  // namespace sdb
