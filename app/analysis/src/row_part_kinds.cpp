// The bench and stability part kinds: each part checked and the parts merged by its job's code.
#include "app/analysis/row_part_kinds.hpp"

#include <sstream>

namespace tumble::app {
namespace {

/// A kind of row parts: `check_one` checks a part, `merge_ordered` merges parts in shard order.
class RowPartKind : public PartKind {
 public:
  using Check = void (*)(const NamedManifest&);
  using Merge = void (*)(const std::vector<NamedManifest>&, const std::filesystem::path&,
                         std::ostream&);

  RowPartKind(const char* name, Check check_one, Merge merge_ordered)
      : name_(name), check_one_(check_one), merge_ordered_(merge_ordered) {}

  std::string name() const override { return name_; }

  void check(const NamedManifest& part) const override { check_one_(part); }

  MergeOutcome merge(const std::vector<NamedManifest>& parts, const std::filesystem::path& output,
                     const std::function<bool()>& /*interrupted*/) const override {
    std::vector<NamedManifest> ordered;
    for (const std::size_t i : check_parts_cover_job(parts)) ordered.push_back(parts[i]);
    std::ostringstream summary;
    merge_ordered_(ordered, output, summary);
    return {false, summary.str()};
  }

 private:
  const char* name_;
  Check check_one_;
  Merge merge_ordered_;
};

}  // namespace

const PartKind& bench_parts() {
  static const RowPartKind kind("bench", check_bench_part, merge_bench_parts);
  return kind;
}

const PartKind& stability_parts() {
  static const RowPartKind kind("stability", check_stability_part, merge_stability_parts);
  return kind;
}

}  // namespace tumble::app
