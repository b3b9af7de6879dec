// A stand-in for LinuxCNC's commander (src/live/linuxcnc_bridge.py, "command") for the tests of
// the server's calibration routes: it logs every request line it receives to argv[2], answers
// with the status record argv[1] (and three zero HAL values), and holds an MDI unanswered until an
// "abort" line arrives (a move that lasts until it is stopped), then answers it "aborted".
#pragma once

namespace pkm::test {

inline const char* kCommanderStandIn = R"PY(
import json, sys
record = json.loads(sys.argv[1])
log = open(sys.argv[2], "a")
moving = None
for line in sys.stdin:
    log.write(line)
    log.flush()
    r = json.loads(line)
    if r.get("op") == "abort":
        if moving is not None:
            print(json.dumps({"id": moving, "ok": False, "error": "aborted"}), flush=True)
            moving = None
        continue
    if r.get("op") == "mdi":
        moving = r.get("id")
        continue
    print(json.dumps({"id": r.get("id"), "ok": True, "status": record, "values": [0, 0, 0]}),
          flush=True)
)PY";

}  // namespace pkm::test
