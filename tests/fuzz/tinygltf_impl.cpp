// tinygltf compiled from its header for the fuzz build, so that it is instrumented (coverage for
// libFuzzer, AddressSanitizer) like the rest of the loading path; the other builds link Debian's
// shared library. Images are never decoded here (io/gltf/gltf_file.cpp installs its own loader).
#define TINYGLTF_IMPLEMENTATION
#define TINYGLTF_NO_STB_IMAGE
#define TINYGLTF_NO_STB_IMAGE_WRITE
#include <tiny_gltf.h>
