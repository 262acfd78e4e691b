// The part-kind registry (app/farm/part_kind.hpp): kinds found by name, an unknown kind refused
// in one line naming the part, a kind given twice refused.
#include "app/farm/part_kind.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <stdexcept>

#include "base/errors.hpp"

namespace tumble::app {
namespace {

using ::testing::HasSubstr;

/// A kind that only says its name and counts its merges.
class NamedOnlyKind : public PartKind {
 public:
  explicit NamedOnlyKind(std::string name) : name_(std::move(name)) {}
  std::string name() const override { return name_; }
  void check(const NamedManifest&) const override {}
  MergeOutcome merge(const std::vector<NamedManifest>& parts, const std::filesystem::path&,
                     const std::function<bool()>&) const override {
    return {false, name_ + " " + std::to_string(parts.size()) + "\n"};
  }

 private:
  std::string name_;
};

NamedManifest manifest_of(const std::string& part, const std::string& kind) {
  NamedManifest named;
  named.part = part;
  named.manifest.kind = kind;
  return named;
}

TEST(PartKinds, FindsEachKindByItsName) {
  const NamedOnlyKind bench("bench"), video("render");
  const PartKinds kinds({&bench, &video});
  EXPECT_EQ(&kinds.of(manifest_of("a", "render")), &video);
  EXPECT_EQ(&kinds.of(manifest_of("b", "bench")), &bench);
  EXPECT_EQ(kinds.names(), (std::vector<std::string>{"bench", "render"}));
  EXPECT_EQ(
      kinds.of(manifest_of("a", "render")).merge({manifest_of("a", "render")}, "out", {}).summary,
      "render 1\n");
}

TEST(PartKinds, UnknownKindIsOneLineNamingThePart) {
  const NamedOnlyKind bench("bench");
  const PartKinds kinds({&bench});
  try {
    kinds.of(manifest_of("parts/p0", "teleport"));
    FAIL() << "no error";
  } catch (const InputError& error) {
    EXPECT_STREQ(error.what(), "parts/p0: teleport parts cannot be merged by this tumble");
  }
}

TEST(PartKinds, KindGivenTwiceIsRefused) {
  const NamedOnlyKind first("bench"), second("bench");
  EXPECT_THROW(PartKinds({&first, &second}), std::invalid_argument);
}

}  // namespace
}  // namespace tumble::app
