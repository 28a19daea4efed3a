#pragma once
// The scene of the departure tests (solver and `fragmpm run`): body 0 is a one-particle steel
// pellet (the lattice point (25.25, 10.25) mm of s = 0.5 mm) flying at 100 m/s towards +x; body 1
// a steel block pushed by a traction on its left side, 12 mm away from the pellet's path. The
// pellet is first, so its removal renumbers the block's particles and its load.
#include <string>

namespace fragmpm::test_support {

/// The scene text with the domain's upper x bound, the `[grid] outside` policy, the step count and
/// any further TOML appended at the end (e.g. an `[output]` table).
inline std::string departure_scene(const std::string& max_x, const std::string& outside,
                                   int max_steps, const std::string& tail = "") {
  return R"(
[grid]
cell_size = "1 mm"
min = ["0 mm", "0 mm"]
max = [")" +
         max_x + R"(", "20 mm"]
outside = ")" +
         outside + R"("
[time]
dt = "0.05 us"
[[materials]]
name = "steel"
E = "200 GPa"
nu = 0.3
density = "7.8 g/cm3"
[[bodies]]
name = "pellet"
material = "steel"
shape = "box"
min = ["25 mm", "10 mm"]
max = ["25.5 mm", "10.5 mm"]
velocity = ["100 m/s", "0 m/s"]
[[bodies]]
name = "block"
material = "steel"
shape = "box"
min = ["2 mm", "2 mm"]
max = ["12 mm", "8 mm"]
[[loads]]
body = "block"
side = "-x"
traction = ["1 MPa", "0 MPa"]
[stop]
max_steps = )" +
         std::to_string(max_steps) + "\n" + tail;
}

}  // namespace fragmpm::test_support
