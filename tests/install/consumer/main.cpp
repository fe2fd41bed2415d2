// Uses the installed coinroll API: the scene file named on the command line (under the contract's names: loadScene,
// Trajectory, column, SceneError), its columns, a still in memory.
// Prints the columns t and energy (every row, 17 digits) for the test to compare with the CSV of
// `coinroll simulate`, then the still's size and how many of its pixels are not the background.
#include <coinroll/coinroll.h>

#include <cstdio>
#include <exception>

int main(int argc, char** argv) {
  try {
    if (argc != 2) {
      std::fputs("usage: consumer SCENE.json\n", stderr);
      return 2;
    }
    const coinroll::Scene scene = coinroll::loadScene(argv[1]);
    const coinroll::Trajectory trajectory = coinroll::simulate(scene, 0.05);
    for (std::size_t row = 0; row < trajectory.rows(); ++row) {
      std::printf("%.17g,%.17g\n", trajectory.column("t")[row], trajectory.column("energy")[row]);
    }
    const coinroll::Image still = coinroll::renderStill(scene, 0.25);
    long differing = 0;
    for (std::size_t i = 4; i < still.rgba.size(); i += 4) {
      if (still.rgba[i] != still.rgba[0] || still.rgba[i + 1] != still.rgba[1] || still.rgba[i + 2] != still.rgba[2]) {
        ++differing;
      }
    }
    std::printf("still %dx%d, %ld pixels unlike the first, version %s\n", still.width, still.height, differing,
                coinroll::version().c_str());
    try {
      coinroll::Scene::fromJson(
          R"({"coin": {"shape": "disk", "radius": 0.0375, "mass": 0.4}, "initial": {}, "duration": -1})");
      std::puts("a bad scene was accepted");
      return 1;
    } catch (const coinroll::SceneError& e) {
      std::printf("bad scene refused: %s\n", e.what());
    }
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "consumer: %s\n", e.what());
    return 1;
  }
}
