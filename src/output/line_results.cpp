#include "pcsim/output/line_results.hpp"

#include "pcsim/output/en50318.hpp"
#include "pcsim/output/h5_file.hpp"
#include "pcsim/output/run_results.hpp"

namespace pcsim::output {

std::vector<ZoneStatistics> zone_statistics(const std::vector<catenary::LineZone>& zones,
                                            const ContactHistory& h, double cutoff_hz) {
  const auto filtered = filter_uniformly_sampled(h.time, h.force, cutoff_hz);
  std::vector<ZoneStatistics> out;
  for (const auto& zone : zones) {
    ZoneStatistics z;
    z.zone = zone;
    z.complete = !h.x.empty() && h.x.front() <= zone.from_x && h.x.back() >= zone.to_x;
    if (z.complete) z.force = force_statistics(h.x, filtered, h.force, zone.from_x, zone.to_x);
    out.push_back(z);
  }
  return out;
}

namespace {

nlohmann::json zone_json(const ZoneStatistics& z) {
  nlohmann::json j = {{"name", z.zone.name},
                      {"overlap", z.zone.overlap},
                      {"from_x", z.zone.from_x},
                      {"to_x", z.zone.to_x},
                      {"complete", z.complete}};
  if (z.complete) j.update(force_statistics_json(z.force));
  return j;
}

}  // namespace

nlohmann::json write_line_results(const OutputDir& out, const catenary::CatenaryMesh& mesh,
                                  const std::vector<ContactHistory>& histories, double cutoff_hz) {
  H5File h5(out.file("contact_wires.h5"));
  std::vector<std::string> names;
  for (int w : mesh.contact_wire_list()) names.push_back(mesh.wires[w].name);
  h5.write_strings("/contact_wires", names);
  nlohmann::json json = nlohmann::json::array();
  for (const auto& h : histories) {
    const std::string g = "/pantographs/" + h.name;
    const std::size_t n = h.time.size(), nw = names.size();
    std::vector<double> wires(n * nw, 0.0);
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t w = 0; w < nw && w < h.wire_force[i].size(); ++w)
        wires[i * nw + w] = h.wire_force[i][w];
    h5.write(g + "/time", h.time);
    h5.write(g + "/position", h.x);
    h5.write(g + "/contact_force", h.force);
    h5.write(g + "/wire_force", wires, n, nw);
    nlohmann::json zones = nlohmann::json::array();
    for (const auto& z : zone_statistics(mesh.zones, h, cutoff_hz)) zones.push_back(zone_json(z));
    json.push_back({{"name", h.name}, {"zones", zones}});
  }
  return json;
}

}  // namespace pcsim::output
