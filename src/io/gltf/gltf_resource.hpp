#pragma once
/// External resources of a glTF asset (buffer and image URIs): resolved strictly inside the model's
/// folder, and served to tinygltf through file-system callbacks that read nothing else.
#include <tiny_gltf.h>

#include <filesystem>
#include <map>
#include <string>

namespace sm {

/// Throws InputError "'<file>': <element>: <problem>", e.g. element "accessors[3]": the error of
/// every glTF reader (here, the lowest of them).
[[noreturn]] void throw_gltf_error(const std::filesystem::path& file, const std::string& element,
                                   const std::string& problem);

/// Decodes the percent-encoding of a URI reference (RFC 3986 §2.1: "%20" is a space, "+" stays a
/// plus). Returns false for a '%' not followed by two hex digits.
bool percent_decode(const std::string& uri, std::string& out);

/// The file a relative `uri` of glTF element `element` (e.g. "buffers[0]") refers to, after
/// percent-decoding, relative to the folder of `model`. Throws InputError
/// "'<model>': <element>.uri '<uri>': <why>" when the URI has a scheme or is absolute, resolves
/// (lexically, or through a symlink) outside the model's folder, names nothing or names something
/// other than a regular file. `what` is "buffer" or "image" for the not-found message.
std::filesystem::path resolve_gltf_resource(const std::filesystem::path& model,
                                            const std::string& element, const std::string& uri,
                                            const char* what);

/// The resources tinygltf may read: the path tinygltf asks for (its base folder joined with its
/// own decoding of the URI) mapped to the file resolve_gltf_resource checked.
class GltfResourceFiles {
 public:
  explicit GltfResourceFiles(std::string base_dir) : base_dir_(std::move(base_dir)) {}
  /// Allows tinygltf to read `file` for `uri`.
  void add(const std::string& uri, const std::filesystem::path& file);
  /// Callbacks that read only the added files (through io/input_file), and nothing else.
  tinygltf::FsCallbacks callbacks();

 private:
  static bool exists(const std::string& path, void* self);
  static std::string expand(const std::string& path, void*);
  static bool read(std::vector<unsigned char>* out, std::string* err, const std::string& path,
                   void* self);
  static bool write(std::string* err, const std::string&, const std::vector<unsigned char>&,
                    void*);
  std::string base_dir_;
  std::map<std::string, std::filesystem::path> files_;
};

}  // namespace sm
