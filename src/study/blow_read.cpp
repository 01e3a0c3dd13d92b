#include "blow_read.hpp"

#include <fstream>
#include <nlohmann/json.hpp>

namespace barimpact::detail {

BlowRead read_blow(const std::filesystem::path& run_dir) {
  BlowRead row;
  std::ifstream in(run_dir / "summary.json");
  if (!in) return row;
  try {
    const auto j = nlohmann::json::parse(in);
    const auto& b = j.at("blow");
    if (b.is_null()) return row;
    auto number = [](const nlohmann::json& v) { return v.is_number() ? v.get<double>() : BlowRead::nan; };
    row.set = number(b.at("set"));
    const bool refusal = row.set == 0.0;  // the hammer did not move the pile: infinite blow counts
    row.blows_per_m = refusal ? std::numeric_limits<double>::infinity() : number(b.at("blows_per_m"));
    row.blows_per_250mm = refusal ? std::numeric_limits<double>::infinity() : number(b.at("blows_per_250mm"));
    row.max_compression = number(b.at("max_compression").at("value"));
    row.max_tension = number(b.at("max_tension").at("value"));
    row.enthru = number(b.at("enthru"));
    row.transfer_ratio = number(b.at("transfer_ratio"));
    row.finished = b.at("finished").get<bool>();
    if (b.contains("stroke")) row.stroke = number(b.at("stroke"));
    if (b.contains("first_set")) row.first_set = number(b.at("first_set"));
    row.blows_run = b.value("blows_run", 1);
  } catch (const std::exception&) {
    return BlowRead{};  // not a summary barimpact wrote whole
  }
  return row;
}

}  // namespace barimpact::detail
