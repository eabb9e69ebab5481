// The `munkberg` Format (formats/munkberg/munkberg_format.h): option parsing, the shape set, and the shared parallel
// block loop (formats/common/block_codec.h); per-block seeds derive from (seed, block index) (solvers/seeding.h),
// so the bytes do not depend on the thread count.
#include "formats/munkberg/munkberg_format.h"

#include <cmath>
#include <memory>
#include <string>

#include "core/error.h"
#include "formats/common/block_codec.h"
#include "formats/common/block_solver.h"
#include "formats/munkberg/munkberg_encoder.h"
#include "formats/munkberg/munkberg_modes.h"
#include "solvers/lattice_polish/lattice_polish_solver.h"
#include "solvers/registry.h"
#include "solvers/seeding.h"

namespace blocklab {

namespace {

constexpr const char* kName = "munkberg";

OptionSpec spec(const char* name, OptionType type, const char* default_value, std::vector<std::string> choices,
                const char* help, double lo = 0.0, double hi = 0.0) {
  OptionSpec out;
  out.name = name;
  out.type = type;
  out.default_value = default_value;
  out.choices = std::move(choices);
  out.help = help;
  out.min_value = lo;
  out.max_value = hi;
  return out;
}

struct Setup {
  munkberg::ModeContext context;   // shapes, ext_s3tc space, encoder settings
  std::uint64_t seed = 1;
};

Setup make_setup(const FormatOptions& options) {
  Setup setup;
  const std::string& shapes_path = option_text(options, "shapes");
  setup.context.shapes = shapes_path.empty() ? munkberg::default_shape_set() : munkberg::load_shape_set(shapes_path);
  munkberg::EncoderSettings& settings = setup.context.settings;

  munkberg::ChromaSettings& chroma = settings.chroma;
  const std::string& solver_name = option_text(options, "solver");
  chroma.solver = &find_solver(solver_name);
  SolverOptions given = parse_solver_option_list(option_text(options, "solver_options"), "solver_options", kName);
  if (solver_name == "nlopt" && given.count("algorithm") == 0) given["algorithm"] = option_text(options, "nlopt_algorithm");
  try {
    chroma.solver_options = resolve_solver_options(*chroma.solver, given);
  } catch (const Error& e) {
    fail(std::string(kName) + ": solver_options", e.what());
  }
  if (solver_name == "procrustes") chroma.procrustes_options = munkberg::procrustes_options_of(chroma.solver_options);
  chroma.warm_start = option_bool(options, "warm_start");
  chroma.polish = option_bool(options, "polish");
  SolverOptions polish = {{"radius", std::to_string(option_int(options, "polish_radius"))}};
  // Coordinate-wise descent: a neighbourhood limit below 3^4 makes lattice_polish move one coordinate at a time.
  if (option_text(options, "polish_search") == "coordinate") polish["full_neighbourhood_limit"] = "1";
  chroma.polish_options = resolve_solver_options(lattice_polish_solver(), polish);
  chroma.polish_candidates = static_cast<int>(option_int(options, "polish_candidates"));
  chroma.polish_margin = option_real(options, "polish_margin");
  chroma.polish_error = option_text(options, "polish_error") == "fit" ? munkberg::ChromaSettings::PolishError::fit
                                                                   : munkberg::ChromaSettings::PolishError::log2rgb;
  chroma.error_kind =
      option_text(options, "chroma_error") == "linear" ? ShapeErrorKind::linear : ShapeErrorKind::stretched;
  chroma.alpha = option_real(options, "alpha");
  chroma.search = option_text(options, "chroma_search") == "per_shape" ? munkberg::ChromaSettings::Search::per_shape
                                                                        : munkberg::ChromaSettings::Search::global;
  chroma.search_candidates = static_cast<int>(option_int(options, "search_candidates"));
  chroma.search_refined = static_cast<int>(option_int(options, "search_refined"));
  chroma.search_tie_limit = static_cast<int>(option_int(options, "search_tie_limit"));
  chroma.search_per_shape = static_cast<int>(option_int(options, "search_per_shape"));
  chroma.skip_constant = option_bool(options, "skip_constant");
  chroma.constant_tolerance = option_real(options, "constant_tolerance");
  settings.luma_radius = static_cast<int>(option_int(options, "luma_radius"));
  settings.skip_mode_bound = option_bool(options, "skip_mode_bound");
  settings.good_enough = option_real(options, "good_enough");
  chroma.good_enough = settings.good_enough;
  settings.modes = munkberg::parse_mode_list(option_text(options, "modes"));
  setup.context.ext_s3tc_space =
      option_text(options, "ext_s3tc_space") == "logyuv" ? munkberg::ExtS3tcSpace::logyuv : munkberg::ExtS3tcSpace::rgb;
  settings.ext_s3tc.space = setup.context.ext_s3tc_space;
  settings.ext_s3tc.refine_passes = static_cast<int>(option_int(options, "ext_s3tc_refine"));
  settings.dct_refine_passes = static_cast<int>(option_int(options, "dct_refine"));
  settings.index_metric =
      option_text(options, "index_metric") == "fit" ? munkberg::IndexMetric::fit : munkberg::IndexMetric::log2rgb;
  // log2rgb indices are chosen after the chroma fit (assign_chroma_indices_log2): the fit's own would be overwritten.
  chroma.fit_indices = settings.index_metric == munkberg::IndexMetric::fit;
  setup.seed = static_cast<std::uint64_t>(option_int(options, "seed"));
  return setup;
}

class MunkbergFormat final : public Format {
 public:
  std::string name() const override { return kName; }
  std::string description() const override {
    return "Munkberg 2008 8 bpp HDR: logYuv, shape II (8-bit log-lum endpoints + 4-bit indices, 2x1-subsampled "
           "shape-transform chroma) / shape I (3-bit indices, per-texel chroma), plus the section 6 modes ext_s3tc, "
           "two_plane and dct (option modes), prefix-coded mode selector";
  }
  std::vector<OptionSpec> option_specs() const override {
    return {
        spec("solver", OptionType::choice, "procrustes", {"procrustes", "anneal", "interval_bb", "nlopt"},
             "chroma shape-fit solver (section 7.1): procrustes = Procrustes analysis + clustering (the paper's), "
             "anneal = simulated annealing, interval_bb = certified interval branch-and-bound, nlopt = any NLopt "
             "algorithm (nlopt_algorithm)"),
        spec("nlopt_algorithm", OptionType::text, "LN_SBPLX", {}, "NLopt algorithm name when solver=nlopt"),
        spec("solver_options", OptionType::text, "", {},
             "options of the chosen solver as 'key=value,key=value' (e.g. iterations=4000 for anneal, max_boxes=100000 "
             "for interval_bb)"),
        spec("warm_start", OptionType::boolean, "true", {},
             "non-procrustes solvers start from the Procrustes answer"),
        spec("chroma_search", OptionType::choice, "global", {"global", "per_shape"},
             "how the 8 shapes are searched with solver=procrustes: global = one clustering per block and mode, all "
             "(shape, correspondence) candidates ranked together, the best few refined and evaluated in the polish "
             "error; per_shape = one full solver run per shape (always used by the other solvers)"),
        spec("search_candidates", OptionType::integer, "64", {},
             "chroma_search=global: candidates (over all shapes) snapped and evaluated in the polish error", 1, 488),
        spec("search_refined", OptionType::integer, "8", {},
             "chroma_search=global: best-ranked candidates refined (clamp-aware descent) before evaluation", 0, 488),
        spec("search_tie_limit", OptionType::integer, "16", {},
             "chroma_search=global: extra candidates evaluated when they tie with the last kept one (exact fits)", 0,
             488),
        spec("search_per_shape", OptionType::integer, "1", {},
             "chroma_search=global: each shape's best candidates evaluated even when outside search_candidates", 0,
             61),
        spec("skip_constant", OptionType::boolean, "true", {},
             "skip rule (chroma_search=global): blocks whose chroma points coincide (within constant_tolerance) skip "
             "the candidate ranking; their chroma is the closed-form scale-0 fit (same bytes at tolerance 0)"),
        spec("constant_tolerance", OptionType::real, "0", {},
             "skip_constant: max-norm chroma distance under which a block counts as constant (0 = exactly; e.g. "
             "0.004 ~ half a 7-bit base-colour step for near-constant blocks)", 0.0, 1.0),
        spec("skip_mode_bound", OptionType::boolean, "true", {},
             "skip rule: a shape mode is not encoded when a lower bound of its log2[RGB] error from its luminance fit "
             "(decoded-black texels exactly, other texels by their luminance ratio, shape II pairs by the error of a "
             "shared chroma factor) shows it cannot beat the best mode so far (same bytes)"),
        spec("good_enough", OptionType::real, "0", {},
             "skip rule (approximate; 0 = off): a block error (squared log2[RGB] differences summed over 16 texels x "
             "3 channels) at which the search stops: once the best mode so far is at most this the remaining modes "
             "are not tried, and (polish_error=log2rgb) a shape already this good is not polished nor any shape "
             "after one that is; e.g. 0.1 (an RMS log2 error of 0.046 per channel)", 0.0, 1e6),
        spec("polish", OptionType::boolean, "true", {},
             "lattice polish of the base colours after the solver (section 7.1)"),
        spec("polish_radius", OptionType::integer, "1", {}, "lattice steps searched around each base coordinate",
             1, 8),
        spec("polish_search", OptionType::choice, "full", {"full", "coordinate"},
             "polish neighbourhood: full = every combination of the 4 coordinates within the radius (3^4 = 81 at "
             "radius 1), coordinate = one coordinate at a time (lattice_polish's coordinate descent)"),
        spec("polish_candidates", OptionType::integer, "2", {},
             "how many of the best-fitting shapes per mode are polished (0 = all 8)", 0, 8),
        spec("polish_margin", OptionType::real, "0", {},
             "chroma_search=global: shapes after the best-ranked one are polished only while their unpolished error "
             "is at most (1 + margin) times its error (0 = always; a speed / quality trade)", 0.0, 1000.0),
        spec("polish_error", OptionType::choice, "log2rgb", {"log2rgb", "fit"},
             "error of the base-colour polish and of the final shape choice: log2rgb = the block's reconstruction "
             "error (eq. 1) with its decoded luminance, fit = the shape-fit error (chroma_error)"),
        spec("chroma_error", OptionType::choice, "nonlinear", {"nonlinear", "linear"},
             "shape-fit error: linear = eq. 11, nonlinear = section 7.2's f(x) = x^alpha on both sides"),
        spec("alpha", OptionType::real, "0.455", {}, "exponent of the nonlinear chroma error (section 7.2)", 0.001,
             1.0),
        spec("luma_radius", OptionType::integer, "2", {},
             "log-luminance endpoint neighbourhood search radius in codes (section 7.3, Fig. 9); 0 = min/max", 0, 16),
        spec("index_metric", OptionType::choice, "log2rgb", {"log2rgb", "fit"},
             "final chroma index per texel/pair: log2rgb = smallest log2[RGB] error of the decoded texels, fit = "
             "nearest landmark in the shape-fit error"),
        spec("modes", OptionType::text, "both", {},
             "modes competing per block: comma-separated list of shape_ii, shape_i, ext_s3tc, two_plane, dct (section "
             "6's rejected modes), or both (= shape_ii,shape_i, the 2008 format) or all"),
        spec("ext_s3tc_space", OptionType::choice, "rgb", {"rgb", "logyuv"},
             "line space of the extended S3TC mode (section 6.1): rgb (log-coded RGB888-like endpoints, linear RGB "
             "palette) or logyuv (Ybar, u, v line); recorded in side data"),
        spec("ext_s3tc_refine", OptionType::integer, "4", {},
             "coordinate-descent passes over the extended S3TC endpoint codes (0 = quantised line fit only)", 0, 16),
        spec("dct_refine", OptionType::integer, "2", {},
             "coordinate-descent passes over the DCT mode's codes in the log2[RGB] error (section 6.2; 0 = nearest "
             "codes only)", 0, 16),
        spec("shapes", OptionType::text, "", {},
             "YAML file of the 8 template shapes (empty: the built-in set, formats/munkberg/shapes.yaml)"),
    };
  }
  std::vector<std::string> modes() const override {
    std::vector<std::string> names;
    for (const munkberg::BlockModeModel& m : munkberg::block_mode_models()) names.push_back(m.name);
    return names;   // BlockMode order: the block_modes index
  }
  // 2: the mode selector became a prefix code (shape I: selector 1,0 and a 2-bit anchor index; section 6 modes).
  // 3: the default chroma search is global (one clustering per block and mode, candidates of all shapes ranked
  // together; option chroma_search=per_shape gives revision 2's bytes).
  // 4: the fixed-rate DCT mode (selector 1,1,1,1); two-plane's selector became 1,1,1,0 with a mask anchor (its
  // blocks moved by one bit; shape II / shape I / ext_s3tc bytes are unchanged).
  int revision() const override { return 4; }
  int block_bytes(const FormatOptions&) const override { return munkberg::kBlockBytes; }

  EncodedTexture encode(const Image& image, const FormatOptions& options,
                        const CodecContext& context) const override {
    validate_encoder_input(image, kName);
    reject_invalid_texels(image);
    const Setup setup = make_setup(options);
    // One chroma workspace per worker thread (its scratch buffers, reused across that worker's blocks).
    EncodedTexture texture = encode_blocks(
        *this, image, options, context, munkberg::kBlockBytes,
        [] { return std::make_unique<munkberg::ChromaWorkspace>(); },
        [&](const BlockTexels& texels, std::size_t index, std::uint8_t* out, munkberg::ChromaWorkspace& workspace) {
          // modes() order = BlockMode = the block_modes index.
          return static_cast<int>(munkberg::encode_best_block(
              texels, setup.context, derive_stream_seed(setup.seed, index), out, nullptr, &workspace));
        });
    texture.side_data[munkberg::kShapeSideDataKey] = munkberg::shape_set_to_side_data(setup.context.shapes);
    texture.side_data[munkberg::kExtS3tcSpaceKey] = {static_cast<double>(setup.context.ext_s3tc_space)};
    if (setup.context.settings.modes[static_cast<std::size_t>(munkberg::BlockMode::dct)])
      texture.side_data[munkberg::kDctTablesSideDataKey] = munkberg::dct_tables_fingerprint(setup.context.dct());
    return texture;
  }

  Image decode(const EncodedTexture& texture, const CodecContext& context) const override {
    munkberg::ModeContext mode_context;
    mode_context.shapes = munkberg::shape_set_of(texture.side_data);
    mode_context.ext_s3tc_space = munkberg::ext_s3tc_space_of(texture.side_data);
    const auto fingerprint = texture.side_data.find(munkberg::kDctTablesSideDataKey);
    // Blocks of a DCT-enabled encode decode through the tables they were made with: refuse other tables.
    if (fingerprint != texture.side_data.end() &&
        fingerprint->second != munkberg::dct_tables_fingerprint(mode_context.dct()))
      fail(kName, std::string("side data '") + munkberg::kDctTablesSideDataKey +
                      "': the texture was encoded with other DCT tables than this build's "
                      "(formats/munkberg/dct_tables.yaml was retrained); re-encode it");
    return decode_blocks(*this, texture, context, rgb_only_decoded_channels(texture.channels),
                         [&](const std::uint8_t* bytes, std::size_t) {
                           return munkberg::decode_any_block(bytes, mode_context);
                         });
  }

 private:
  // logYuv needs finite, non-negative RGB (what the input policy guarantees): anything else is an Error naming the
  // pixel, never a NaN endpoint code (a NaN cast to an integer code would be undefined behaviour).
  static void reject_invalid_texels(const Image& image) {
    for (int y = 0; y < image.height; ++y)
      for (int x = 0; x < image.width; ++x)
        for (int channel = 0; channel < 3; ++channel) {
          const float value = image.texel(x, y)[channel];
          if (!(std::isfinite(value) && value >= 0.0f))
            fail(kName, "pixel (" + std::to_string(x) + ", " + std::to_string(y) + ") channel " +
                            std::string(1, "RGB"[channel]) + " is " + std::to_string(value) +
                            " (not finite and non-negative; apply the input policy before encoding)");
        }
  }
};

}  // namespace

const Format& munkberg_format() {
  static const MunkbergFormat format;
  return format;
}

}  // namespace blocklab
