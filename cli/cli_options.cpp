#include "cli/cli_options.hpp"

#include <memory>

#include "io/sampling_spec.hpp"

namespace fleetmerge {

void AddMethodOptions(CLI::App& app, PairOptions& options) {
  // The sampling texts are parsed after CLI11 is done, so a bad one gets our message.
  auto hough = std::make_shared<std::string>("all");
  auto spectra = std::make_shared<std::string>("all");
  auto seed = std::make_shared<unsigned>(0);
  app.add_option("--n-theta", options.hypotheses.hough.n_theta, "Hough theta bins over 180 degrees")
      ->check(CLI::Range(8, 3600))
      ->capture_default_str();
  app.add_option("--rho-step", options.hypotheses.hough.rho_step_cells,
                 "Hough rho bin height in cells (n_rho = map extent / rho step)")
      ->check(CLI::Range(0.1, 100.0))
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
