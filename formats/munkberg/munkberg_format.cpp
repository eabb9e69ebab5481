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
#include "formats/munkberg/munkberg_problems.h"
#include "solvers/lattice_polish/lattice_polish_solver.h"
#include "solvers/procrustes/procrustes_solver.h"
#include "solvers/registry.h"
#include "solvers/seeding.h"

namespace blocklab {

namespace {

constexpr const char* kName = "munkberg";
constexpr const char* kBuiltin = "builtin";

// Every option of the format as typed values; the member initialisers are the `thorough` search (the default of
// revisions 3 and 4), and munkberg_option_table() declares each option once.
struct MunkbergOptions {
  std::string solver = kBuiltin;
  std::string procrustes_options;
  std::string solver_options;
  bool warm_start = true;
  int search_candidates = 64;
  int search_refined = 8;
  int search_tie_limit = 16;
  int search_per_shape = 1;
  double constant_tolerance = 0.0;
  double good_enough = 0.0;
  double mode_predictor = 0.5;
  bool polish = true;
  int polish_radius = 1;
  std::string polish_search = "full";
  int polish_candidates = 2;
  double polish_margin = 0.0;
  std::string polish_error = "log2rgb";
  std::string chroma_error = "nonlinear";
  double alpha = 0.455;
  int luma_radius = 2;
  std::string index_metric = "log2rgb";
  HdrBlockError error = HdrBlockError::log2_floor;
  std::string modes = "all";
  std::string ext_s3tc_space = "rgb";
  int ext_s3tc_refine = 4;
  int dct_refine = 2;
  std::string shapes;
};

std::vector<std::string> solver_choices() {
  std::vector<std::string> names = {kBuiltin};
  for (const Solver* solver : all_solvers()) names.push_back(solver->name());
  return names;
}

const OptionTable<MunkbergOptions>& munkberg_option_table() {
  using O = MunkbergOptions;
  static const auto table = OptionTable<O>()
      .choice("solver", &O::solver, solver_choices(),
              "chroma shape fit (section 7.1): builtin = the global search (one clustering per block and mode, the "
              "(shape, correspondence) candidates of all 8 shapes ranked together by their Procrustes bound, the best "
              "refined and evaluated in the polish error; settings procrustes_options), or any solver of the library "
              "run on each shape's problem (procrustes = the paper's per-shape Procrustes fit; anneal, interval_bb, "
              "nlopt, ...; settings solver_options)")
      .text("procrustes_options", &O::procrustes_options,
            "solver=builtin: the procrustes solver's options of the global search, 'key=value,key=value' "
            "(max_clusters, min_clusters, kmeans_iterations, svd; see `blocklab list`)")
      .text("solver_options", &O::solver_options,
            "solver=NAME: that solver's options as 'key=value,key=value' (e.g. iterations=4000 for anneal, "
            "max_boxes=100000 for interval_bb, algorithm=LN_BOBYQA for nlopt)")
      .boolean("warm_start", &O::warm_start, "solvers other than procrustes start from the Procrustes answer")
      .integer("search_candidates", &O::search_candidates, 1, 488,
               "solver=builtin: candidates (over all shapes) snapped and evaluated in the polish error")
      .integer("search_refined", &O::search_refined, 0, 488,
               "solver=builtin: best-ranked candidates refined (clamp-aware descent) before evaluation")
      .integer("search_tie_limit", &O::search_tie_limit, 0, 488,
               "solver=builtin: extra candidates evaluated when they tie with the last kept one (exact fits)")
      .integer("search_per_shape", &O::search_per_shape, 0, 61,
               "solver=builtin: each shape's best candidates evaluated even when outside search_candidates")
      .real("constant_tolerance", &O::constant_tolerance, 0.0, 1.0,
            "solver=builtin: blocks whose chroma points all lie within this max-norm distance skip the candidate "
            "ranking and take the closed-form scale-0 fit (0 = exactly constant chroma, where the ranking gives the "
            "same answer; e.g. 0.004 ~ half a 7-bit base-colour step)")
      .real("good_enough", &O::good_enough, 0.0, 1e6,
            "skip rule (approximate; 0 = off): a block error (squared log2[RGB] differences summed over 16 texels x "
            "3 channels) at which the search stops: once the best mode so far is at most this the remaining modes "
            "are not tried, and (polish_error=log2rgb) a shape already this good is not polished nor any shape "
            "after one that is; e.g. 0.1 (an RMS log2 error of 0.046 per channel)")
      .real("mode_predictor", &O::mode_predictor, 0.0, 1.0,
            "skip rule for the section 6 modes (approximate; 0 = off): ext_s3tc and dct are tried after the other "
            "modes and skipped when this factor x the error of their unrefined fit is at least the best error so "
            "far; two_plane when this factor x (its luminance bound + shape I's chroma share) is")
      .boolean("polish", &O::polish, "lattice polish of the base colours after the solver (section 7.1)")
      .integer("polish_radius", &O::polish_radius, 1, 8, "lattice steps searched around each base coordinate")
      .choice("polish_search", &O::polish_search, {"full", "coordinate"},
              "polish neighbourhood: full = every combination of the 4 coordinates within the radius (3^4 = 81 at "
              "radius 1), coordinate = one coordinate at a time (lattice_polish's coordinate descent)")
      .integer("polish_candidates", &O::polish_candidates, 0, 8,
               "how many of the best-fitting shapes per mode are polished (0 = all 8)")
      .real("polish_margin", &O::polish_margin, 0.0, 1000.0,
            "solver=builtin: shapes after the best-ranked one are polished only while their unpolished error is at "
            "most (1 + margin) times its error (0 = always; a speed / quality trade)")
      .choice("polish_error", &O::polish_error, {"log2rgb", "fit"},
              "error of the base-colour polish and of the final shape choice: log2rgb = the block's reconstruction "
              "error (eq. 1) with its decoded luminance, fit = the shape-fit error (chroma_error)")
      .choice("chroma_error", &O::chroma_error, {"nonlinear", "linear"},
              "shape-fit error: linear = eq. 11, nonlinear = section 7.2's f(x) = x^alpha on both sides")
      .real("alpha", &O::alpha, 0.001, 1.0, "exponent of the nonlinear chroma error (section 7.2)")
      .integer("luma_radius", &O::luma_radius, 0, 16,
               "log-luminance endpoint neighbourhood search radius in codes (section 7.3, Fig. 9); 0 = min/max")
      .choice("index_metric", &O::index_metric, {"log2rgb", "fit"},
              "final chroma index per texel/pair: log2rgb = smallest log2[RGB] error of the decoded texels, fit = "
              "nearest landmark in the shape-fit error")
      .choice("error", &O::error, hdr_block_error_choices(),
              "weights of the base-colour polish error (polish_error=log2rgb; the mode choice stays log2[RGB]): "
              "log2_floor = eq. 1 unweighted, log2_skip = source zeros weigh 0, mpsnr_weighted = each squared log2 "
              "difference weighted by the mPSNR exposure weight (formats/common/hdr_block_error.h)")
      .text("modes", &O::modes,
            "modes competing per block: comma-separated list of shape_ii, shape_i, ext_s3tc, two_plane, dct (section "
            "6's rejected modes), or both (= shape_ii,shape_i, the 2008 format) or all")
      .choice("ext_s3tc_space", &O::ext_s3tc_space, {"rgb", "logyuv"},
              "line space of the extended S3TC mode (section 6.1): rgb (log-coded RGB888-like endpoints, linear RGB "
              "palette) or logyuv (Ybar, u, v line); recorded in side data")
      .integer("ext_s3tc_refine", &O::ext_s3tc_refine, 0, 16,
               "coordinate-descent passes over the extended S3TC endpoint codes (0 = quantised line fit only)")
      .integer("dct_refine", &O::dct_refine, 0, 16,
               "coordinate-descent passes over the DCT mode's codes in the log2[RGB] error (section 6.2; 0 = nearest "
               "codes only)")
      .text("shapes", &O::shapes,
            "YAML file of the 8 template shapes (empty: the built-in set, formats/munkberg/shapes.yaml)");
  return table;
}

// The presets as changes to the thorough search (MunkbergOptions' initialisers). Measured side by side with astcenc
// (benchmarks/bench_munkberg, docs/benchmarks-munkberg.md): fast 0.29-0.41x astcenc -medium's time, medium
// 0.53-0.76x, both with a lower log2[RGB] on desk, memorial and cathedral; thorough 1.8-3.6x.
const FormatOptions& fast_changes() {
  static const FormatOptions changes = {
      {"good_enough", "4"},        {"polish_candidates", "1"},     {"search_candidates", "8"},
      {"search_refined", "2"},     {"search_tie_limit", "4"},      {"polish_search", "coordinate"},
      {"luma_radius", "1"},        {"procrustes_options", "max_clusters=2,svd=tables"},
      {"mode_predictor", "1"}};
  return changes;
}
const FormatOptions& medium_changes() {
  static const FormatOptions changes = {
      {"good_enough", "2"},    {"polish_candidates", "1"}, {"search_candidates", "32"},
      {"search_refined", "4"}, {"luma_radius", "1"},       {"procrustes_options", "max_clusters=2,svd=tables"}};
  return changes;
}
// Section 7.1 as written: each template shape fitted on its own by Procrustes analysis, then polished.
const FormatOptions& paper_changes() {
  static const FormatOptions changes = {{"solver", "procrustes"}, {"modes", "both"}, {"mode_predictor", "0"}};
  return changes;
}

std::vector<FormatPreset> munkberg_presets() {
  const FormatOptions thorough_values = munkberg_option_table().to_options(MunkbergOptions{});
  // Each preset lists every option any preset changes, so switching presets never keeps another preset's value.
  const auto complete = [&](const FormatOptions& changes) {
    FormatOptions values = changes;
    for (const FormatOptions* other : {&fast_changes(), &medium_changes(), &paper_changes()})
      for (const auto& entry : *other) values.emplace(entry.first, thorough_values.at(entry.first));
    return values;
  };
  return {{"fast", "a quarter of the medium candidates, coordinate polish, mode predictor factor 1",
           complete(fast_changes()), {}},
          {kDefaultPreset, "quality limit good_enough=2, smaller candidate budgets, all modes with the mode predictor (faster than astcenc -medium)",
           complete(medium_changes()), {}},
          {"thorough", "the full global search (every exact skip rule, no quality limit), all modes with the mode predictor", complete({}), {}},
          {"paper", "the paper's two shape modes, per-shape Procrustes fits as section 7.1 describes (slow)", complete(paper_changes()), {}}};
}

struct Setup {
  munkberg::ModeContext context;   // shapes, ext_s3tc space, encoder settings
  std::uint64_t seed = 1;
};

SolverOptions resolve_text_options(const Solver& solver, const std::string& key, const std::string& text) {
  try {
    return resolve_solver_options(solver, parse_solver_option_list(text, key, kName));
  } catch (const Error& e) {
    fail(std::string(kName) + ": " + key, e.what());
  }
}

Setup make_setup(const FormatOptions& resolved, const munkberg::ExactSpeedups& speedups) {
  const MunkbergOptions options = munkberg_option_table().from_resolved(resolved);
  Setup setup;
  setup.context.shapes =
      options.shapes.empty() ? munkberg::default_shape_set() : munkberg::load_shape_set(options.shapes);
  munkberg::EncoderSettings& settings = setup.context.settings;

  munkberg::ChromaSettings& chroma = settings.chroma;
  if (options.solver == kBuiltin) {
    // The format's own global search, on the procrustes solver's clustering and fits.
    if (!options.solver_options.empty())
      fail(kName, "option 'solver_options' is for solver=NAME; the builtin search takes procrustes_options");
    chroma.solver = &procrustes_solver();
    chroma.search = munkberg::ChromaSettings::Search::global;
    chroma.solver_options = resolve_text_options(procrustes_solver(), "procrustes_options", options.procrustes_options);
    chroma.procrustes_options = munkberg::procrustes_options_of(chroma.solver_options);
  } else {
    // procrustes_options, like the other builtin-only options, is not used here (a preset may have set it).
    chroma.solver = &find_solver(options.solver);
    chroma.search = munkberg::ChromaSettings::Search::per_shape;
    chroma.solver_options = resolve_text_options(*chroma.solver, "solver_options", options.solver_options);
  }
  chroma.warm_start = options.warm_start;
  chroma.polish = options.polish;
  SolverOptions polish = {{"radius", std::to_string(options.polish_radius)}};
  // Coordinate-wise descent: a neighbourhood limit below 3^4 makes lattice_polish move one coordinate at a time.
  if (options.polish_search == "coordinate") polish["full_neighbourhood_limit"] = "1";
  chroma.polish_options = resolve_solver_options(lattice_polish_solver(), polish);
  chroma.polish_candidates = options.polish_candidates;
  chroma.polish_margin = options.polish_margin;
  chroma.polish_error = options.polish_error == "fit" ? munkberg::ChromaSettings::PolishError::fit
                                                      : munkberg::ChromaSettings::PolishError::log2rgb;
  chroma.error_kind = options.chroma_error == "linear" ? ShapeErrorKind::linear : ShapeErrorKind::stretched;
  chroma.alpha = options.alpha;
  chroma.search_candidates = options.search_candidates;
  chroma.search_refined = options.search_refined;
  chroma.search_tie_limit = options.search_tie_limit;
  chroma.search_per_shape = options.search_per_shape;
  chroma.skip_constant = speedups.skip_constant;
  chroma.constant_tolerance = options.constant_tolerance;
  settings.luma_radius = options.luma_radius;
  settings.skip_mode_bound = speedups.skip_mode_bound;
  settings.good_enough = options.good_enough;
  chroma.good_enough = settings.good_enough;
  settings.mode_predictor = options.mode_predictor;
  settings.modes = munkberg::parse_mode_list(options.modes);
  setup.context.ext_s3tc_space =
      options.ext_s3tc_space == "logyuv" ? munkberg::ExtS3tcSpace::logyuv : munkberg::ExtS3tcSpace::rgb;
  settings.ext_s3tc.space = setup.context.ext_s3tc_space;
  settings.ext_s3tc.refine_passes = options.ext_s3tc_refine;
  settings.dct_refine_passes = options.dct_refine;
  settings.error = options.error;
  settings.index_metric = options.index_metric == "fit" ? munkberg::IndexMetric::fit : munkberg::IndexMetric::log2rgb;
  // log2rgb indices are chosen after the chroma fit (assign_chroma_indices_log2): the fit's own would be overwritten.
  chroma.fit_indices = settings.index_metric == munkberg::IndexMetric::fit;
  setup.seed = static_cast<std::uint64_t>(option_int(resolved, "seed"));
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
  // Defaults are the medium preset's values (what an encode without options uses).
  std::vector<OptionSpec> option_specs() const override {
    FormatOptions medium = munkberg_option_table().to_options(MunkbergOptions{});
    for (const auto& entry : medium_changes()) medium[entry.first] = entry.second;
    return munkberg_option_table().specs(munkberg_option_table().from_resolved(medium));
  }
  std::vector<ModeSpec> mode_table() const override { return munkberg::mode_table(); }
  std::vector<BlockProblem> block_problems() const override { return munkberg_block_problems(); }
  std::vector<FormatPreset> presets() const override { return munkberg_presets(); }
  // 2: the mode selector became a prefix code (shape I: selector 1,0 and a 2-bit anchor index; section 6 modes).
  // 3: the default chroma search is global (one clustering per block and mode, candidates of all shapes ranked
  // together; option chroma_search=per_shape gives revision 2's bytes).
  // 4: the fixed-rate DCT mode (selector 1,1,1,1); two-plane's selector became 1,1,1,0 with a mask anchor (its
  // blocks moved by one bit; shape II / shape I / ext_s3tc bytes are unchanged).
  // 5: every preset but paper lets all five modes compete (modes=all) with the mode predictor (mode_predictor 0.5;
  // fast 1): the section 6 modes run after the shape modes and only where their estimate can win.
  int revision() const override { return 5; }
  // Revision 5 changed the encoder only: files of revision 4 decode the same.
  int decoder_revision() const override { return 4; }
  int block_bytes(const FormatOptions&) const override { return munkberg::kBlockBytes; }

  EncodedTexture encode(const Image& image, const FormatOptions& options,
                        const CodecContext& context) const override {
    return encode_with(image, options, context, munkberg::ExactSpeedups{});
  }

  EncodedTexture encode_with(const Image& image, const FormatOptions& options, const CodecContext& context,
                             const munkberg::ExactSpeedups& speedups) const {
    validate_encoder_input(image, kName);
    reject_invalid_texels(image);
    const Setup setup = make_setup(options, speedups);
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
    // A texture encoded with custom shapes decodes only through them: without their side data the built-in shapes
    // would decode other colours, silently.
    const auto shapes_option = texture.options.find("shapes");
    if (shapes_option != texture.options.end() && !shapes_option->second.empty() &&
        texture.side_data.count(munkberg::kShapeSideDataKey) == 0)
      fail(kName, std::string("the texture was encoded with the custom shapes '") + shapes_option->second +
                      "' but carries no side data '" + munkberg::kShapeSideDataKey + "' to decode them with");
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

const MunkbergFormat& the_format() {
  static const MunkbergFormat format;
  return format;
}

}  // namespace

const Format& munkberg_format() { return the_format(); }

namespace munkberg {

EncodedTexture encode_with_speedups(const Image& image, const FormatOptions& resolved, const CodecContext& context,
                                    const ExactSpeedups& speedups) {
  return the_format().encode_with(image, resolved, context, speedups);
}

ModeContext mode_context_of(const FormatOptions& resolved) { return make_setup(resolved, ExactSpeedups{}).context; }

}  // namespace munkberg

}  // namespace blocklab
