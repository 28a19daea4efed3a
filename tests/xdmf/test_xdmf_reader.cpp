// The .xmf beside a run file as ParaView's Xdmf3 reader sees it, loaded with the XDMF 3 library
// (Debian's libxdmf-dev): every frame a Polyvertex point set at its time, damage the first
// attribute, vectors of 3 and tensors of 9 components on the points, 2D data padded with z = 0
// (F_zz = 1).
#include <gtest/gtest.h>
#include <unistd.h>

#include <XdmfAttribute.hpp>
#include <XdmfAttributeCenter.hpp>
#include <XdmfAttributeType.hpp>
#include <XdmfDomain.hpp>
#include <XdmfGeometry.hpp>
#include <XdmfGridCollection.hpp>
#include <XdmfReader.hpp>
#include <XdmfTime.hpp>
#include <XdmfTopology.hpp>
#include <XdmfTopologyType.hpp>
#include <XdmfUnstructuredGrid.hpp>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include "../support/temp_run_path.hpp"
#include "fragmpm/mpm/run_file.hpp"

namespace fragmpm::mpm {
namespace {

std::string temp_path(const std::string& name) {
  return test_support::temp_run_path("fragmpm_xdmf", name);
}

template <int D>
Particles<D> random_particles(std::size_t n, bool thermal, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Particles<D> p;
  p.resize(n, thermal);
  for (std::size_t i = 0; i < n; ++i) {
    for (int a = 0; a < D; ++a) {
      p.x[i](a) = u(rng);
      p.v[i](a) = u(rng);
      for (int b = 0; b < D; ++b) {
        p.F[i](a, b) = (a == b ? 1.0 : 0.0) + 0.1 * u(rng);
        p.stress[i](a, b) = 1e6 * u(rng);
        p.domain[i](a, b) = 1e-3 * u(rng);
      }
    }
    p.volume0[i] = 1 + u(rng);
    p.mass[i] = 2 + u(rng);
    p.damage[i] = 0.5 + 0.5 * u(rng);
    p.surface[i] = static_cast<std::uint8_t>(i % 2);
    p.body[i] = static_cast<std::int32_t>(i % 3);
    p.material[i] = static_cast<std::int32_t>(i % 5);
    if (thermal) p.temperature[i] = 300 + 10 * u(rng);
  }
  return p;
}

struct Written {
  double time;
  std::size_t points;
};

/// Loads the .xmf of `path` with the XDMF 3 library and checks every frame against `frames` and
/// the particles of `last` (the last frame written).
template <int D>
void check_xmf(const std::string& path, const std::vector<Written>& frames,
               const Particles<D>& last) {
  const std::string xmf = std::filesystem::path(path).replace_extension(".xmf").string();
  const shared_ptr<XdmfDomain> domain =
      shared_dynamic_cast<XdmfDomain>(XdmfReader::New()->read(xmf));
  ASSERT_TRUE(domain);
  ASSERT_EQ(domain->getNumberGridCollections(), 1u);
  const shared_ptr<XdmfGridCollection> collection = domain->getGridCollection(0);
  ASSERT_EQ(collection->getNumberUnstructuredGrids(), frames.size());
  for (unsigned g = 0; g < collection->getNumberUnstructuredGrids(); ++g) {
    SCOPED_TRACE("frame " + std::to_string(g));
    const shared_ptr<XdmfUnstructuredGrid> grid = collection->getUnstructuredGrid(g);
    const std::size_t n = frames[g].points;
    ASSERT_TRUE(grid->getTime());
    EXPECT_EQ(grid->getTime()->getValue(), frames[g].time);
    EXPECT_EQ(grid->getTopology()->getType(), XdmfTopologyType::Polyvertex());
    grid->getTopology()->read();
    EXPECT_EQ(grid->getTopology()->getNumberElements(), n);
    grid->getGeometry()->read();
    EXPECT_EQ(grid->getGeometry()->getNumberPoints(), n);
    ASSERT_GT(grid->getNumberAttributes(), 0u);
    EXPECT_EQ(grid->getAttribute(0)->getName(), "damage");
    EXPECT_EQ(grid->getNumberAttributes(), last.temperature.empty() ? 12u : 13u);
    for (unsigned a = 0; a < grid->getNumberAttributes(); ++a) {
      const shared_ptr<XdmfAttribute> attribute = grid->getAttribute(a);
      const std::string name = attribute->getName();
      SCOPED_TRACE(name);
      attribute->read();
      EXPECT_EQ(attribute->getCenter(), XdmfAttributeCenter::Node());
      unsigned components = 1;
      if (name == "v" || name == "r1" || name == "r2") {
        EXPECT_EQ(attribute->getType(), XdmfAttributeType::Vector());
        components = 3;
      } else if (name == "F" || name == "stress") {
        EXPECT_EQ(attribute->getType(), XdmfAttributeType::Tensor());
        components = 9;
      } else {
        EXPECT_EQ(attribute->getType(), XdmfAttributeType::Scalar());
      }
      ASSERT_EQ(attribute->getSize(), n * components);
      if (g + 1 != frames.size()) continue;
      // The values of the last frame, component by component.
      for (std::size_t p = 0; p < n; ++p) {
        if (name == "v") {
          for (int i = 0; i < 3; ++i)
            EXPECT_EQ(attribute->getValue<double>(3 * p + i), i < D ? last.v[p](i) : 0.0);
        } else if (name == "F" || name == "stress") {
          const Mat<D>& m = name == "F" ? last.F[p] : last.stress[p];
          for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) {
              const double pad = i == 2 && j == 2 && name == "F" ? 1.0 : 0.0;
              EXPECT_EQ(attribute->getValue<double>(9 * p + 3 * i + j),
                        i < D && j < D ? m(i, j) : pad);
            }
        } else if (name == "damage") {
          EXPECT_EQ(attribute->getValue<double>(p), last.damage[p]);
        } else if (name == "body") {
          EXPECT_EQ(attribute->getValue<int>(p), last.body[p]);
        } else if (name == "id") {
          EXPECT_EQ(attribute->getValue<int>(p), last.id[p]);
        }
      }
    }
  }
}

RunMeta meta() {
  RunMeta m;
  m.scene_path = "test.toml";
  m.wall_names = {"top"};
  return m;
}

TEST(Xdmf3Library, LoadsEveryFrameOfA2DRun) {
  const std::string path = temp_path("two_d");
  std::vector<Written> frames;
  Particles<2> last;
  {
    auto run = RunFile<2>::create(path, meta(), false);
    for (int k = 0; k < 4; ++k) {
      last =
          random_particles<2>(k == 3 ? 5 : 8, true, 10 + k);  // a smaller last frame: hyperslab ids
      run.write_frame(10 * k, 2.5e-6 * k, last, {});
      frames.push_back({2.5e-6 * k, last.size()});
    }
    // Truncation drops frames 2 and 3 and their padded copies; the rest must still load.
    run.truncate_after(10);
    frames.resize(2);
    last = random_particles<2>(6, true, 99);
    run.write_frame(20, 7e-6, last, {});
    frames.push_back({7e-6, last.size()});
  }
  check_xmf<2>(path, frames, last);
  // Reopening for a restart rewrites the .xmf from the file alone.
  { auto run = RunFile<2>::open_existing(path); }
  check_xmf<2>(path, frames, last);
}

TEST(Xdmf3Library, LoadsA3DRun) {
  const std::string path = temp_path("three_d");
  auto run = RunFile<3>::create(path, meta(), false);
  const Particles<3> p = random_particles<3>(7, false, 3);
  run.write_frame(0, 0.0, p, {});
  run.write_frame(5, 1e-6, p, {});
  check_xmf<3>(path, {{0.0, 7}, {1e-6, 7}}, p);
}

}  // namespace
}  // namespace fragmpm::mpm
