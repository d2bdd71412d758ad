#include "cli/help.hpp"

#include "pipeline/outputs/frame_output.hpp"
#include "pipeline/sequence/input_kinds.hpp"

namespace sm::cli {

// The help of each command: its description (usage, what it does) and footer (outputs, exit
// status); CLI11 lists the options between them (main.cpp defines them).
const char* const kHelp = R"(Usage: seqmassage [options] CONFIG.json
       seqmassage measure [options] MESH REFERENCE   (see seqmassage measure --help)
       seqmassage merge [options] OUTPUT_DIR         (see seqmassage merge --help)
       seqmassage config --reference | --complete FILE

Commands:
  (none)   run the job of CONFIG.json
  measure  print the paper's measures of a mesh against a reference mesh
  merge    combine the shards of a sequence job (--shard I/N) into the outputs of one run
  config   --reference: print every config key, its type, default and meaning (Markdown);
           --complete FILE: print FILE with every key its job resolves (defaults added)

Runs the job of a JSON config file (see README.md; paths in it are relative to the file's folder),
by its "job" key:
  sequence    corrects texture swimming in a captured mesh sequence (Mesh Massage, section 3.1):
              every frame takes the template frame's triangle shapes and stays on its surface
  remesh      brings a remesh closer to its source surface (section 3.3)
  crossparam  copies the triangle shapes of a source mesh onto a target mesh with the same
              connectivity (section 3.2)
  smooth      evens out the triangles while keeping the surface and its sharp features (section 4)
)";

// The footer's inputs and outputs of a sequence come from the table of input kinds
// (sm::inputs_help) and the output registry (sm::outputs_help), between these parts
// (run_help_footer).
const char* const kHelpInputs = "Inputs of a sequence, one of these keys in \"input\":\n";
const char* const kHelpOutputs = "\nOutputs of a sequence, under \"output.dir\":\n";

const char* const kHelpFooter = R"(  records/<frame>.json        what made each frame, its summary row, its outputs' SHA-256
  summary.csv, report.json    one row per frame; config, totals, warnings, failures
A shard (--shard I/N) names its own summary.shard-I-of-N.csv, report.shard-I-of-N.json and
iterations.shard-I-of-N.csv; 'seqmassage merge' writes summary.csv, report.json,
iterations.csv, and sequence.glb or sequence.pc2/.mdd and rest.obj from them.
Outputs of the other jobs: <input file name> (in "output.format"), measures.csv (before and
after), report.json and, with "per_triangle_csv", triangles.csv.
--frames, --resume and --shard apply to sequences only. Every file is written to a temporary
name and renamed when complete, so a killed run leaves complete files only.

Exit status:
  0    every frame (or the mesh) was processed
  1    internal error (a bug; please report it)
  2    usage or config error: bad option, missing config file, invalid JSON, unknown key,
       wrong type or out-of-range value, an output folder that would overwrite an input
  3    input error: a malformed frame, template or glTF file (the message names the glTF
       element), frames with different vertex counts or faces; for merge, missing,
       incomplete or inconsistent shards (named, with the frames concerned)
  4    I/O error: a file or folder cannot be read or written; or another run holds the
       output folder's lock (.seqmassage.lock; a shard's .seqmassage-shard-I-of-N.lock), the
       message names its host and pid
  5    processing error: some frames failed (the optimizer failed, non-finite positions, or
       more folded triangles than "checks" allow; reason in summary.csv and on stderr); they
       are written unchanged (or not at all: "output": {"on_failure": "skip"}) and the other
       frames are complete. For a single-mesh job, the optimizer failed: no mesh is written,
       report.json holds the reason
  130  interrupted (Ctrl-C, SIGINT): the frames in flight were finished; the frames done are
       written and listed in summary.csv; --resume continues
  143  terminated (SIGTERM, as schedulers send): the same as 130
  129  hung up (SIGHUP: the terminal or ssh connection closed): the same as 130
A second SIGINT, SIGTERM or SIGHUP ends the program at once; like SIGKILL, it leaves complete
files only, and --resume continues. SIGPIPE is ignored: with stderr or stdout closed (piped into
'head'), the run goes on and its outputs complete.
)";

const char* const kMergeHelp = R"(Usage: seqmassage merge [options] OUTPUT_DIR

Combines the shards of a sequence job run with --shard I/N (every shard writing into OUTPUT_DIR)
into the outputs of one run: summary.csv and report.json, byte for byte what a single unsharded
run of the same config writes (with "output": {"timings": false}; with timings on, the seconds
differ), and for "format": "gltf" sequence.glb (for "pc2" or "mdd": sequence.pc2 or
sequence.mdd and rest.obj), assembled from every shard's positions/ files (this reads the
input again). It checks first that all N shard reports
(report.shard-I-of-N.json) are there and complete, that every shard ran the same job (the same
config apart from "threads" and "frames_in_flight", template and program: their hashes), and
that every selected frame is in exactly one shard, with its record and outputs. The shard files
are left in place.

The shards of a track job are merged the same way: summary.csv, report.json and the
whole-sequence files from every shard's report and frame files, the job planned again from the
config (its raw frames and template must be reachable); the seams (first frames of the shards
after the first, tracked from the template) are listed on stderr and in report.json.
)";

const char* const kMergeHelpFooter = R"(Exit status: 0 merged; 3 missing or inconsistent shards or frames (the message names them and
the command that redoes them), nothing written; 4 I/O error, or a shard or run still holds the
folder's lock; 5 merged, but some frames failed or were lost (as for a run).
)";

const char* const kMeasureHelp = R"(Usage: seqmassage measure [options] MESH REFERENCE

Prints the paper's measures of MESH against REFERENCE (any two .obj, .off or .ply meshes), the
same report as the remesh, crossparam and smooth jobs write:
  - Metro-style one-sided distances MESH -> REFERENCE and REFERENCE -> MESH (max, mean, RMS,
    absolute and relative to the bounding-box diagonal of both), sampled on vertices, edges and
    inside triangles, and the symmetric Hausdorff distance;
  - the radius ratio 2r/R of both meshes' triangles (min, mean; 1 = equilateral);
  - the shear distortion (eq. 8) of MESH against the --template, or against REFERENCE when it has
    MESH's connectivity (max, mean, p95, histogram);
  - REFERENCE's sharp edges: their distance to MESH, and with the same connectivity the change of
    their dihedral angles.
)";

const char* const kMeasureHelpFooter = R"(Exit status: 0 success, 2 usage error, 3 input error (malformed mesh, template of another
connectivity), 4 I/O error.
)";

std::string run_help_footer() {
  return kHelpInputs + inputs_help() + kHelpOutputs + outputs_help() + kHelpFooter;
}

}  // namespace sm::cli
