// `pkm serve` as a user runs it: --port 0 prints the real port, every example program's POST
// /api/gcode/run answers equal `pkm gcode run --report` of the same files (every key but the
// program's name), and Ctrl-C (SIGINT) stops it cleanly with exit code 0.
#include <httplib.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <nlohmann/json.hpp>
#include <regex>

#include "support/cli_fixture.hpp"

namespace pkm::test {
namespace PKM_TEST_NS {

using Json = nlohmann::json;

/// A `pkm serve --port 0` process and the port it printed.
class Served {
 public:
  Served() {
    int out[2];
    if (::pipe(out) != 0) throw std::runtime_error("pipe");
    pid_ = ::fork();
    if (pid_ == 0) {
      ::dup2(out[1], STDOUT_FILENO);
      ::close(out[0]);
      ::execl(PKM_BINARY, PKM_BINARY, "serve", "--port", "0", static_cast<char*>(nullptr));
      ::_exit(127);
    }
    ::close(out[1]);
    std::string line;
    char c = 0;
    while (::read(out[0], &c, 1) == 1 && c != '\n') line += c;
    ::close(out[0]);
    first_line_ = line;
    std::smatch m;
    if (std::regex_match(
            line, m, std::regex(R"(pkm: serving http://127\.0\.0\.1:(\d+)/\?token=[0-9a-f]{64})")))
      port_ = std::stoi(m[1].str());
  }
  ~Served() {
    if (pid_ > 0 && !stopped_) {
      ::kill(pid_, SIGKILL);
      ::waitpid(pid_, nullptr, 0);
    }
  }
  /// Sends SIGINT and returns the exit status.
  int interrupt() {
    ::kill(pid_, SIGINT);
    int status = 0;
    ::waitpid(pid_, &status, 0);
    stopped_ = true;
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  }
  int port() const { return port_; }
  const std::string& firstLine() const { return first_line_; }

 private:
  pid_t pid_ = -1;
  int port_ = 0;
  bool stopped_ = false;
  std::string first_line_;
};

TEST_F(CliTest, ServeAnswersAsTheCliAndStopsOnCtrlC) {
  Served served;
  ASSERT_GT(served.port(), 0) << served.firstLine();
  httplib::Client client("127.0.0.1", served.port());
  client.set_read_timeout(120, 0);
  const std::string ex = std::string(PKM_SOURCE_DIR) + "/examples/gcode/";
  const std::string tools = slurp(ex + "tools.tbl");
  struct Case {
    const char* program;
    const char* machine;
    bool tools;
  };
  for (const Case& c : {Case{"sphere.ngc", "hexapod-default", true},
                        Case{"hexapod_contour.ngc", "hexapod-default", false},
                        Case{"exechon_contour.ngc", "mxt700s-like", false},
                        Case{"drilling.ngc", "hexapod-default", true},
                        Case{"pocket_loops.ngc", "hexapod-default", true}}) {
    std::vector<std::string> args{"gcode",
                                  "run",
                                  ex + c.program,
                                  "--machine",
                                  c.machine,
                                  "--report",
                                  path("report.json"),
                                  "--force"};
    if (c.tools) args.insert(args.end(), {"--tool-table", ex + "tools.tbl"});
    const CliRun cli = pkm(args);
    ASSERT_LE(cli.code, 1) << cli.err;
    Json body{{"machine", c.machine}, {"name", c.program}, {"program", slurp(ex + c.program)}};
    if (c.tools) body["tool_table"] = tools;
    const auto r = client.Post("/api/gcode/run", body.dump(), "application/json");
    ASSERT_TRUE(r);
    ASSERT_EQ(r->status, 200) << r->body;
    Json api = Json::parse(r->body), want = Json::parse(slurp(path("report.json")));
    EXPECT_GT(api["path"]["t"].size(), 1u);
    api.erase("path");
    api.erase("violations");
    api.erase("frames");
    api.erase("program");
    want.erase("program");
    EXPECT_EQ(api, want) << c.program;
  }
  EXPECT_EQ(served.interrupt(), 0);
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::test
