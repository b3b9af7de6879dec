// POST /api/campaign (server-sent events), GET /api/campaigns and GET
// /api/campaign/ID/report.html (docs/web.md): workflow::runCampaign into the server's folder.
#include <fmt/format.h>

#include <optional>

#include "api_state.hpp"
#include "pkm/core/error.hpp"
#include "pkm/io/atomic_file.hpp"
#include "pkm/workflow/campaign.hpp"

namespace pkm::server {
namespace {

using detail::finiteOrNull;
using detail::Json;

/// Campaign outputs a server keeps (each a folder of files and its report).
constexpr std::size_t kMaxCampaigns = 8;

std::string event(const char* name, const Json& data) {
  return fmt::format("event: {}\ndata: {}\n\n", name, data.dump());
}

/// Whether the row's improvement is larger than its combined U: true, false or null.
Json significantJson(const workflow::CampaignRow& row) {
  const std::optional<bool> s = row.significant();
  return s ? Json(*s) : Json(nullptr);
}

Json stepJson(const workflow::CampaignStepResult& st) {
  Json rows = Json::array();
  for (const workflow::CampaignRow& row : st.rows)
    rows.push_back({{"quantity", row.quantity},
                    {"unit", row.unit},
                    {"before", finiteOrNull(row.before)},
                    {"after", finiteOrNull(row.after)},
                    {"target", row.target ? Json(*row.target) : Json(nullptr)},
                    {"paper", row.paper},
                    {"pass", row.pass()},
                    {"before_U", finiteOrNull(row.before_U)},
                    {"after_U", finiteOrNull(row.after_U)},
                    {"significant", significantJson(row)}});
  return {{"id", st.id}, {"title", st.title}, {"rows", rows}};
}

Json stepsJson(const workflow::CampaignResult& r) {
  Json steps = Json::array();
  for (const workflow::CampaignStepResult& st : r.steps) steps.push_back(stepJson(st));
  return steps;
}

}  // namespace

void Api::runCampaign(CampaignJob& job, const std::function<bool(const std::string&)>& write) {
  State& s = *state_;
  bool connected = true;
  auto send = [&](const std::string& chunk) {
    if (connected && !write(chunk)) {
      connected = false;
      job.cancel.cancel();  // the client left: stop at the next check point
    }
  };
  workflow::RunControl control;
  control.cancel = &job.cancel;
  control.progress = [&](const workflow::ProgressEvent& e) {
    send(event("progress",
               {{"stage", e.stage},
                {"index", e.index},
                {"count", e.count},
                {"elapsed", e.elapsed},
                {"message", e.message}}));
  };
  control.notice = [&](const std::string& n) { send(event("notice", {{"message", s.clean(n)}})); };
  const std::string name = fmt::format("campaign-{}", job.id);
  const std::filesystem::path out = s.dir / name;
  {
    const std::lock_guard lock(s.mutex);  // also cancellable by POST /api/jobs/campaign-ID/cancel
    s.running[name] = &job.cancel;
  }
  std::error_code ec;
  try {
    workflow::CampaignOptions o;
    o.campaign = job.campaign;
    o.out = out;
    o.on_step = [&](const workflow::CampaignStepResult& st) { send(event("step", stepJson(st))); };
    const workflow::CampaignResult r = workflow::runCampaign(o, control);
    {
      // The newest kMaxCampaigns outputs are kept (their reports stay served); older ones go.
      const std::lock_guard lock(s.mutex);
      s.campaign_reports[job.id] = r.report;
      while (s.campaign_reports.size() > kMaxCampaigns) {
        std::filesystem::remove_all(s.campaign_reports.begin()->second.parent_path(), ec);
        s.campaign_reports.erase(s.campaign_reports.begin());
      }
    }
    send(event("result",
               {{"id", job.id},
                {"campaign", r.name},
                {"report", fmt::format("/api/campaign/{}/report.html", job.id)},
                {"all_pass", r.all_pass},
                {"steps", stepsJson(r)}}));
  } catch (const workflow::Cancelled&) {
    std::filesystem::remove_all(out, ec);
    send(event("cancelled", {{"id", job.id}}));
  } catch (const std::exception& e) {
    std::filesystem::remove_all(out, ec);
    send(event("error", {{"error", s.clean(e.what())}}));
  }
  {
    const std::lock_guard lock(s.mutex);
    s.running.erase(name);
  }
  job.slot.reset();
}

}  // namespace pkm::server

namespace pkm::server::detail {

Response listCampaigns() {
  Json list = Json::array();
  for (const std::string& name : workflow::builtinCampaignNames()) {
    const workflow::CampaignInfo info = workflow::describeCampaign(name);
    list.push_back({{"name", info.name}, {"steps", info.steps}, {"description", info.description}});
  }
  return json(list);
}

void prepareCampaign(Api::State& s, const Request& r, CampaignJob& job) {
  const Json body = parseObject(r);
  job.campaign = stringField(body, "campaign", "default");
  const std::vector<std::string> names = workflow::builtinCampaignNames();
  if (std::find(names.begin(), names.end(), job.campaign) == names.end())
    throw HttpError(
        400, fmt::format("unknown campaign '{}': GET /api/campaigns lists them", job.campaign));
  job.slot = std::make_shared<JobSlot>(s);
  const std::lock_guard lock(s.mutex);
  job.id = s.next_campaign++;
}

Response campaignReport(Api::State& s, const std::string& id) {
  std::filesystem::path report;
  {
    const std::lock_guard lock(s.mutex);
    const auto it = s.campaign_reports.find(std::stoi(id));
    if (it == s.campaign_reports.end())
      throw HttpError(404, fmt::format("no campaign {} has finished on this server", id));
    report = it->second;
  }
  return {200, "text/html; charset=utf-8", io::readFileText(report), "", "", ""};
}

}  // namespace pkm::server::detail
