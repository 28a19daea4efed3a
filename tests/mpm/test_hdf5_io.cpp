// The HDF5 layer: typed datasets of any rank, extendible datasets, attributes, links, errors.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "fragmpm/mpm/hdf5_io.hpp"

namespace fragmpm::mpm::h5 {
namespace {

/// A path unique to this process (test runs may overlap), removed at exit.
std::string temp_path(const std::string& name) {
  struct Cleanup {
    std::vector<std::string> paths;
    ~Cleanup() {
      std::error_code ec;
      for (const std::string& p : paths) std::filesystem::remove(p, ec);
    }
  };
  static Cleanup cleanup;
  const std::string path =
      ::testing::TempDir() + "fragmpm_hdf5_io_" + std::to_string(getpid()) + "_" + name;
  std::filesystem::remove(path);
  cleanup.paths.push_back(path);
  return path;
}

template <Element T>
void expect_round_trip(const Group& g, const std::string& name, const Dims& dims) {
  std::vector<T> values(element_count(dims));
  for (std::size_t i = 0; i < values.size(); ++i) values[i] = static_cast<T>(i * 7 % 251);
  g.write(name, values, dims);
  const Array<T> back = g.read<T>(name);
  EXPECT_EQ(back.dims, dims) << name;
  EXPECT_EQ(back.values, values) << name;
}

TEST(Hdf5Io, DatasetsOfEveryTypeAndRank) {
  const std::string path = temp_path("types.h5");
  const File file = File::create(path, false);
  const Group g = file.root().require_group("a/b/c");  // nested, created in one call
  expect_round_trip<double>(g, "d", {3, 4, 5});
  expect_round_trip<float>(g, "f", {7});
  expect_round_trip<std::int32_t>(g, "i32", {2, 3});
  expect_round_trip<std::int64_t>(g, "i64", {2, 2, 2, 2});
  expect_round_trip<std::uint8_t>(g, "u8", {300});
  expect_round_trip<double>(g, "scalar", {});
  expect_round_trip<double>(g, "empty", {0, 2});
  EXPECT_TRUE(file.root().exists("a/b/c/d"));
  EXPECT_TRUE(file.root().exists("/a/b"));
  EXPECT_FALSE(file.root().exists("a/x/c"));
  EXPECT_TRUE(file.root().is_group("a/b"));
  EXPECT_TRUE(file.root().is_dataset("a/b/c/u8"));
  EXPECT_FALSE(file.root().is_dataset("a/b"));
  EXPECT_EQ(g.children(),
            (std::vector<std::string>{"d", "empty", "f", "i32", "i64", "scalar", "u8"}));
  EXPECT_EQ(g.open_dataset("d").object_path(), "/a/b/c/d");

  // Integers widen to double on read; doubles are not silently truncated to integers.
  EXPECT_EQ(g.read<double>("i32").values[1], 7.0);
  EXPECT_THROW(g.read<std::int32_t>("d"), RunFileError);

  // Rewriting with another shape replaces the dataset.
  g.write<double>("d", std::vector<double>{1.5, 2.5}, {2});
  EXPECT_EQ(g.read<double>("d").dims, Dims{2});
  EXPECT_THROW(g.write<double>("bad", std::vector<double>{1, 2, 3}, {2, 2}), RunFileError);

  g.remove("d");
  EXPECT_FALSE(g.exists("d"));
  EXPECT_THROW(g.remove("d"), RunFileError);
}

TEST(Hdf5Io, ExtendibleDatasets) {
  const std::string path = temp_path("extendible.h5");
  const File file = File::create(path, false);
  const Dataset ds = file.root().create_extendible<double>("series/force", {2}, 4);
  EXPECT_EQ(ds.dims(), (Dims{0, 2}));
  ds.append_rows(std::vector<double>{1, 2, 3, 4, 5, 6});  // 3 rows
  ds.append_rows(
      std::vector<double>{7, 8, 9, 10, 11, 12, 13, 14, 15, 16});  // 5 rows, across chunks
  EXPECT_EQ(ds.rows(), 8u);
  ds.set_rows(2);
  EXPECT_EQ(file.root().read<double>("series/force").values, (std::vector<double>{1, 2, 3, 4}));
  EXPECT_THROW(ds.append_rows(std::vector<double>{1, 2, 3}), RunFileError);  // not whole rows

  const Dataset steps = file.root().create_extendible<std::int64_t>("series/step", {});
  steps.append_rows(std::vector<std::int64_t>{5, 6, 7});
  EXPECT_EQ(file.root().read<std::int64_t>("series/step").values,
            (std::vector<std::int64_t>{5, 6, 7}));
  // A contiguous dataset cannot be extended.
  const Dataset fixed = file.root().write<double>("fixed", std::vector<double>{1, 2}, {2});
  EXPECT_THROW(fixed.set_rows(5), RunFileError);
}

TEST(Hdf5Io, Attributes) {
  const std::string path = temp_path("attributes.h5");
  {
    const File file = File::create(path, false);
    const Group root = file.root();
    root.set_attribute("pixel_size", 2.5e-6);
    root.set_attribute("count", std::int64_t{-42});
    root.set_attribute("image_path", "images/grains 1.png");
    const std::string big(200000, 'x');  // larger than the 64 KiB compact attribute limit
    root.set_attribute("scene_text", big);
    root.set_attribute("count", std::int64_t{43});  // replaces
    const Dataset ds = root.write<float>("data", std::vector<float>{1.f}, {1});
    ds.set_attribute("units", "Pa");
  }
  const File file = File::open(path, false);
  const Group root = file.root();
  EXPECT_EQ(root.attribute_double("pixel_size"), 2.5e-6);
  EXPECT_EQ(root.attribute_int64("count"), 43);
  EXPECT_EQ(root.attribute_double("count"), 43.0);
  EXPECT_EQ(root.attribute_string("image_path"), "images/grains 1.png");
  EXPECT_EQ(root.attribute_string("scene_text").size(), 200000u);
  EXPECT_EQ(root.open_dataset("data").attribute_string("units"), "Pa");
  EXPECT_TRUE(root.has_attribute("count"));
  EXPECT_FALSE(root.has_attribute("nothing"));
  EXPECT_THROW(root.attribute_int64("pixel_size"), RunFileError);
  EXPECT_THROW(root.attribute_string("count"), RunFileError);
  try {
    root.attribute_double("nothing");
    FAIL() << "expected RunFileError";
  } catch (const RunFileError& e) {
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("'nothing'"), std::string::npos) << e.what();
  }
}

TEST(Hdf5Io, FileErrorsNameThePath) {
  const std::string path = temp_path("errors.h5");
  { const File file = File::create(path, false); }
  EXPECT_THROW(File::create(path, false), RunFileError);
  EXPECT_NO_THROW(File::create(path, true));
  EXPECT_THROW(File::open(path + ".missing", false), RunFileError);
  const std::string text_file = temp_path("not_hdf5.txt");
  { std::ofstream(text_file) << "hello"; }
  try {
    File::open(text_file, false);
    FAIL() << "expected RunFileError";
  } catch (const RunFileError& e) {
    EXPECT_NE(std::string(e.what()).find(text_file), std::string::npos) << e.what();
  }
  const File file = File::open(path, false);
  try {
    file.root().read<double>("frames/000001/x");
    FAIL() << "expected RunFileError";
  } catch (const RunFileError& e) {
    EXPECT_NE(std::string(e.what()).find("frames/000001/x"), std::string::npos) << e.what();
  }
  EXPECT_THROW(file.root().require_group("new"), RunFileError);  // read-only
}

}  // namespace
}  // namespace fragmpm::mpm::h5
