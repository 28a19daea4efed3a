// fragmpm_make_images OUT_DIR [--data DIR]: writes the sample images of images/.
//   OUT_DIR/synthetic/*.png, *.tif   synthetic micrographs with known answers
//   (segment_synthetic.hpp)
//                                    and their ground-truth label images (*_truth.png, 16-bit)
//   with --data DIR (the shared data folder, see images/PROVENANCE.md):
//   OUT_DIR/miocene_sandstone_window.png   800 × 600 window of the sandstone class mask
//   OUT_DIR/miocene_sandstone_pack.png     1000 × 750 window from the same corner (the demo)
//   OUT_DIR/torrey_pines_beach_image.jpg   the beach photograph, re-encoded at JPEG quality 85
//   OUT_DIR/torrey_pines_beach_mask.png    its ground-truth mask, recompressed
// Deterministic: the same build writes the same synthetic images.
#include <cstdio>
#include <filesystem>
#include <opencv2/imgcodecs.hpp>
#include <string>
#include <vector>

#include "fragmpm/pipeline/segment_synthetic.hpp"

namespace fs = std::filesystem;
namespace fp = fragmpm::pipeline;

namespace {

// Window of the sandstone mask: 51 grains of median equivalent diameter ≈ 68 µm at 1 µm/px.
const cv::Rect kSandstoneWindow(3200, 1000, 800, 600);
// The demo's pack: the same top-left corner, large enough for 40 grains clear of its edges.
const cv::Rect kSandstonePack(3200, 1000, 1000, 750);

void write(const fs::path& path, const cv::Mat& image, const std::vector<int>& params = {}) {
  if (!cv::imwrite(path.string(), image, params)) {
    std::fprintf(stderr, "fragmpm_make_images: cannot write %s\n", path.c_str());
    std::exit(1);
  }
  std::printf("%s\n", path.c_str());
}

cv::Mat truth16(const cv::Mat& truth) {
  cv::Mat out;
  truth.convertTo(out, CV_16U);
  return out;
}

const std::vector<int> kPng{cv::IMWRITE_PNG_COMPRESSION, 9};

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2 && !(argc == 4 && std::string(argv[2]) == "--data")) {
    std::fprintf(stderr, "usage: fragmpm_make_images OUT_DIR [--data SHARED_DATA_DIR]\n");
    return 2;
  }
  const fs::path out = argv[1];
  fs::create_directories(out / "synthetic");
  const fs::path syn = out / "synthetic";

  for (const fp::SyntheticImage& s :
       {fp::synthetic_disks(), fp::synthetic_irregular(7), fp::synthetic_touching_pairs(),
        fp::synthetic_border_disks(), fp::synthetic_two_phase()}) {
    write(syn / (s.name + ".png"), s.image, kPng);
    write(syn / (s.name + "_truth.png"), truth16(s.truth), kPng);
  }
  // Noise: σ = 30 grey levels on a grain/background contrast of 130.
  fp::SyntheticImage noisy = fp::synthetic_disks();
  fp::add_gaussian_noise(noisy.image, 30.0, 11);
  write(syn / "noisy_disks.png", noisy.image, kPng);
  // 16-bit TIFF: the touching pairs at 1000 … 52000 with σ = 2000 noise (Deflate compressed).
  fp::SyntheticImage pairs = fp::synthetic_touching_pairs();
  cv::Mat deep = fp::to_16bit(pairs.image);
  fp::add_gaussian_noise(deep, 2000.0, 13);
  write(syn / "touching_pairs_16bit.tif", deep, {cv::IMWRITE_TIFF_COMPRESSION, 8});

  if (argc == 4) {
    const fs::path data = argv[3];
    const cv::Mat mask =
        cv::imread((data / "miocene_sandstone_grain_mask.png").string(), cv::IMREAD_UNCHANGED);
    const cv::Mat photo =
        cv::imread((data / "torrey_pines_beach_image.jpg").string(), cv::IMREAD_COLOR);
    const cv::Mat truth =
        cv::imread((data / "torrey_pines_beach_mask.png").string(), cv::IMREAD_UNCHANGED);
    if (mask.empty() || photo.empty() || truth.empty()) {
      std::fprintf(stderr, "fragmpm_make_images: cannot read the shared images in %s\n",
                   data.c_str());
      return 1;
    }
    write(out / "miocene_sandstone_window.png", mask(kSandstoneWindow).clone(), kPng);
    write(out / "miocene_sandstone_pack.png", mask(kSandstonePack).clone(), kPng);
    write(out / "torrey_pines_beach_image.jpg", photo, {cv::IMWRITE_JPEG_QUALITY, 85});
    write(out / "torrey_pines_beach_mask.png", truth, kPng);
  }
  return 0;
}
