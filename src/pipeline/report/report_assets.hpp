#pragma once
/// The report page's code and style, embedded at build time (cmake/EmbedAssets.cmake generates
/// the definitions from src/pipeline/report/report_page.{js,css} and web/'s bundle), so that the
/// installed program needs no file of the source tree.
namespace sm::report_assets {

extern const char* const page_js;   ///< tables, plots, histogram; starts the player
extern const char* const page_css;
/// The 3D player (three.js bundled by esbuild), or "" when the build had no bundle.
extern const char* const player_js;
/// Why the player is missing ("" when it is there).
extern const char* const player_missing;

}  // namespace sm::report_assets
