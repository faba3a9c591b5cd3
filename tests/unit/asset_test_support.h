// What the asset tests share: the shared assets' folder and reading one as
// a scene (a failure is a test failure, with an empty scene back).
#pragma once

#include <gtest/gtest.h>

#include <string>
#include <utility>

#include "lib/scene/scene_io.h"

namespace lodbake::test {

inline const std::string kAssets = std::string(LODBAKE_TEST_SHARED_DATA) + "/assets/";

inline Scene read_asset(const std::string& path) {
  ImportReport report;
  Result<Scene> scene = read_scene_file(path, {}, &report);
  EXPECT_TRUE(scene.is_ok()) << path << ": " << scene.status().message();
  return scene.is_ok() ? std::move(scene).value() : Scene();
}

}  // namespace lodbake::test
