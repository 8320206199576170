#include "pipeline/cli_options.hpp"

#include <memory>

#include "core/error.hpp"

namespace fleetmerge {

SamplingOptions ParseSampling(const std::string& option, const std::string& text) {
  SamplingOptions s;
  const auto fail = [&]() -> SamplingOptions {
    throw Error("option " + option + ": expected 'all', 'random:F' with F in (0, 1] or 'every:K' " +
                "with K >= 1, got '" + text + "'");
  };
  try {
    std::size_t used = 0;
    if (text == "all") return s;
    if (text.rfind("random:", 0) == 0) {
      s.mode = SamplingMode::kRandomFraction;
      s.fraction = std::stod(text.substr(7), &used);
      if (used != text.size() - 7 || !(s.fraction > 0.0 && s.fraction <= 1.0)) return fail();
      return s;
    }
    if (text.rfind("every:", 0) == 0) {
      s.mode = SamplingMode::kEveryKth;
      s.step = std::stoi(text.substr(6), &used);
      if (used != text.size() - 6 || s.step < 1) return fail();
      return s;
    }
  } catch (const std::logic_error&) {  // stod / stoi: not a number, out of range
  }
  return fail();
}

void AddMethodOptions(CLI::App& app, PairOptions& options) {
  // The sampling texts are parsed after CLI11 is done, so a bad one gets our message.
  auto hough = std::make_shared<std::string>("all");
  auto spectra = std::make_shared<std::string>("all");
  auto seed = std::make_shared<unsigned>(0);
  app.add_option("--n-theta", options.hypotheses.hough.n_theta, "Hough theta bins over 180 degrees")
      ->check(CLI::Range(8, 3600))
      ->capture_default_str();
  app.add_option("--hough-sampling", *hough,
                 "points for the Hough transform: all | random:F | every:K (Section III-D)")
      ->capture_default_str();
  app.add_option("--spectra-sampling", *spectra,
                 "points for the translation search: all | random:F | every:K")
      ->capture_default_str();
  app.add_option("--seed", *seed, "seed of random sampling")->capture_default_str();
  app.add_option("--translation", options.hypotheses.translation.method,
                 "translation method: correlation (2-D FFT, default) or spectra (paper's X/Y)")
      ->transform(CLI::CheckedTransformer(
          std::map<std::string, TranslationMethod>{
              {"correlation", TranslationMethod::kCorrelation2D},
              {"spectra", TranslationMethod::kXySpectra}},
          CLI::ignore_case));
  app.add_flag("!--no-refine", options.refine, "skip the local refinement (paper's method only)");
  app.callback([&options, hough, spectra, seed] {
    options.hypotheses.hough_sampling = ParseSampling("--hough-sampling", *hough);
    options.hypotheses.spectra_sampling = ParseSampling("--spectra-sampling", *spectra);
    options.hypotheses.hough_sampling.seed = *seed;
    options.hypotheses.spectra_sampling.seed = *seed + 1;
  });
}

}  // namespace fleetmerge
