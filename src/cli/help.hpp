#pragma once
/// The help texts of seqmassage's commands: each command's description (usage, what it does)
/// and footer (outputs, exit status); CLI11 lists the options between them.
#include <string>

namespace sm::cli {

extern const char* const kHelp;  ///< `seqmassage --help`, before the options
extern const char* const kMergeHelp;
extern const char* const kMergeHelpFooter;
extern const char* const kMeasureHelp;
extern const char* const kMeasureHelpFooter;

/// `seqmassage --help` after the options: the inputs, every registered output
/// (sm::outputs_help), the other files, the exit statuses.
std::string run_help_footer();

}  // namespace sm::cli
