// The run-file key table in docs/runfile.md is generated from the key declarations
// (`talus keys --markdown`); this test fails when a key is declared or changed without
// regenerating the documentation.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "io/KeyRegistry.hpp"
#include "sim/RunKeys.hpp"

TEST(Docs, RunFileKeyTableMatchesDeclarations) {
  std::ifstream in(std::string(TALUS_TEST_DATA_DIR) + "/../docs/runfile.md");
  ASSERT_TRUE(in) << "docs/runfile.md not found";
  std::ostringstream text;
  text << in.rdbuf();
  const std::string doc = text.str();
  const std::string table = talus::io::describeKeys(talus::talusRunKeys());
  ASSERT_GE(doc.size(), table.size());
  EXPECT_EQ(doc.substr(doc.size() - table.size()), table)
      << "docs/runfile.md is out of date: regenerate its key table with `talus keys --markdown`";
}
