// What the subcommands share: errors and exit codes, CAMERA options, JSON output (docs/FORMATS.md,
// "Command line"). Exit status: 0 success; 1 runtime failure with one line naming the file or value; 2 usage.
#pragma once

#include <CLI/CLI.hpp>
#include <glm/vec3.hpp>
#include <nlohmann/json.hpp>

#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "objects/bounds.h"
#include "perpixel/perpixel_method.h"
#include "texmap/camera.h"
#include "warp/prewarp.h"

namespace rtm::cli {

// A usage error (bad flag value): exit status 2.
struct UsageError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

glm::dvec3 parse_vec3(const std::string& text, const std::string& flag);
// Throws UsageError "<what>X,Y,Z has a coordinate beyond +-1e30" (`what` names the flag) past the camera's limit.
void check_coordinates(const glm::dvec3& v, const std::string& what);
// --level N|auto: N >= 0, or -1 for auto.
int parse_level(const std::string& text);
// --filter point|coverage; coverage needs the two-pass reconstruction. Throws UsageError naming the value.
Filter parse_filter(const std::string& text, Reconstruction method);
// A comma-separated list of procedural relief names (procedural/procedural_media.h); throws UsageError naming the
// unknown one.
std::vector<std::string> parse_relief_names(const std::string& text, const std::string& flag);
// --isa NAME (warp/isa.h): a target this CPU supports ("auto" too). Throws UsageError naming the value when it names
// no target or one this CPU or build lacks; also when RTM_ISA does (that variable chooses for "auto").
Isa parse_isa_arg(const std::string& text, const std::string& flag);
// Throws UsageError when RTM_ISA names no target or one this CPU or build lacks: called first by every subcommand
// that pre-warps, so that a bad variable is exit 2 before any work (not exit 1 at the first pre-warp).
void check_isa_environment();
// A target asked for by name (`asked`, --isa's text; "auto" asks for none) that the pre-warp did not run on (`ran`):
// one warning line naming the kernels that did and why (the fast kernels take neither --exact nor the coverage
// filter, nor outputs past their size limit: fast_prewarp_covers, warp/simd/schedule.h).
void warn_isa_not_run(const std::string& asked, Isa ran, const PrewarpOptions& options);
// --isa LIST: comma-separated targets, each as parse_isa_arg.
std::vector<Isa> parse_isa_list(const std::string& text, const std::string& flag);
void parse_size(const std::string& text, const std::string& flag, int& w, int& h);
// --output-scale N (1 to 8): the relief resampled onto a grid N times finer (warp/upsample.h) so that the pre-warp
// writes a texture N times the source's size in each direction. Throws UsageError naming N when out of range and
// std::runtime_error naming the relief file `path` when the result would be too large.
ReliefTexture apply_output_scale(ReliefTexture relief, int factor, const std::string& path);

// --threads N: 0 (all the machine's) to kMaxThreads; anything else is exit 2 naming the value. More threads than the
// machine has run as many as it has (warp/task_arenas.h arena_threads).
constexpr int kMaxThreads = 1024;
CLI::Option* add_threads_option(CLI::App& app, int& threads, const std::string& what = "Threads");

// Validators of what the user typed (CLI11 runs them on given values only, so a default such as -1 for "not given"
// never reaches them, and typing it is refused): a finite threshold >= 0 (--discontinuity), a frame index 0..2^31-1
// (--camera-path K). The message names the value as typed.
CLI::Validator non_negative_threshold();
CLI::Validator frame_index();
// Whole numbers, one rule for every flag that takes one (the options CLI11 converts, --size WxH, --level, bench's
// lists): decimal digits only, no sign, space, exponent, fraction or 0x; "1e3", "+8", "0x10" and "2.0" are refused
// alike. parse_whole_number reads one (false for anything else, or above `max`); whole_number() is the check for a
// CLI11 integer option, to be added before any range check (whose own message would say "not in range").
bool parse_whole_number(const std::string& text, int& out, int max = std::numeric_limits<int>::max());
CLI::Validator whole_number();
// The first of `flags` typed on `app`'s command line ("" when none was): for a flag that a section the other flags
// leave out would silently ignore.
std::string first_given(const CLI::App& app, std::initializer_list<const char*> flags);
// A list option given empty ("--sizes ''") is refused rather than read as not given (the default set ran).
CLI::Validator non_empty_list();

struct CameraArgs {
    std::string eye, orbit, look_at, up = "0,1,0", size = "512x512";
    double fov = 45.0;
    std::string view_flag;  // the first of --look-at, --up and --fov typed ("" when none was)
    void add_to(CLI::App& app, bool eye_required = false);
    // Builds the camera for what is rendered (its bounds give the orbit centre and the clip planes).
    Camera resolve(const Bounds& bounds) const;
    bool has_eye() const { return !eye.empty() || !orbit.empty(); }
};

// The per-pixel methods' flags render and view both take: --curved-base cylinder|sphere and --quadric-distance
// approximate|exact (quadric silhouettes), --steep-texture builtin|IMG (protruded displacement mapping). Empty: not
// given.
struct PerPixelArgs {
    std::string curved_base, quadric_distance, steep_texture;
    void add_to(CLI::App& app);
    // The settings they give (the papers' defaults otherwise). Throws UsageError naming a value it does not know.
    // The sphere gets as many rows as segments (the cylinder's 4 rows are straight lines).
    PerPixelSettings settings() const;
    // --steep-texture's image, read (IoError naming the file), or nullopt for none or builtin.
    std::optional<ImageRGBA8> steep_image() const;
};

// Writes JSON atomically (write_text_atomically, formats/atomic_file.h).
void write_json(const std::string& path, const nlohmann::json& j);
// For a long job that writes `path` at its end: throws IoError naming the file (given by `flag`) if its folder does
// not exist or cannot be written, so that the job does not run for nothing.
void check_output_file(const std::string& path, const std::string& flag);

// Creates the folder `path` given by `flag` (and its parents) for a job's outputs. Throws UsageError for an empty
// name and IoError "FLAG PATH: cannot create the output folder: REASON" when it cannot be made.
void make_output_folder(const std::string& path, const std::string& flag = "--out");

// Statistics over repeated timings.
nlohmann::json timing_json(std::vector<double> ms);

// Registration of each subcommand (apps/cmd_*.cpp).
void add_prewarp_command(CLI::App& app);
void add_render_command(CLI::App& app);
void add_compare_command(CLI::App& app);
void add_bench_skips_command(CLI::App& app);
void add_view_command(CLI::App& app);
void add_diff_command(CLI::App& app);
void add_bench_command(CLI::App& app);
void add_bench_filter_command(CLI::App& app);
void add_bake_command(CLI::App& app);

}  // namespace rtm::cli
