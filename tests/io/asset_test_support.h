#pragma once
// Shared by the asset tests (test_asset_io.cpp, test_asset_gltf.cpp): a rejected asset's message.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "adaptex/core/errors.h"
#include "adaptex/io/asset_io.h"

namespace adaptex::test {

/// The message of the InvalidInputError (or subclass) that reading \p file throws, or "(no error)".
inline std::string asset_error(const std::filesystem::path& file, const AssetReadOptions& options = {}) {
  try {
    (void)read_textured_asset(file, options);
  } catch (const InvalidInputError& e) {
    return e.what();
  }
  return "(no error)";
}

/// Reading \p file is rejected with one line that contains \p who (the file, and where in it) and \p what.
inline void expect_asset_rejected(const std::filesystem::path& file, const std::string& who, const std::string& what,
                                  const AssetReadOptions& options = {}) {
  const std::string msg = asset_error(file, options);
  EXPECT_NE(msg.find(who), std::string::npos) << "expected '" << who << "' in: " << msg;
  EXPECT_NE(msg.find(what), std::string::npos) << "expected '" << what << "' in: " << msg;
  EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
}

}  // namespace adaptex::test
