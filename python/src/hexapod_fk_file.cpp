// pkm.Hexapod.fk_file: `pkm hexapod fk` on a file, through the same read-solve-print pipeline
// (workflow::solveHexapodFkFile), the output written atomically.
#include "pkm/workflow/hexapod_fk_file.hpp"

#include <fmt/format.h>
#include <pybind11/stl.h>

#include <optional>

#include "hexapod_geometry.hpp"
#include "paths.hpp"
#include "pkm/core/units.hpp"
#include "pkm/io/atomic_file.hpp"

namespace pkm::python {
namespace {

constexpr const char* kFkFileDoc =
    R"doc(Forward kinematics of a CSV file of strut readings into a CSV file of poses, as
`pkm hexapod fk --lengths LENGTHS` does (the same pipeline: the file read a chunk ahead, rows
solved in order, each seeding the next, the poses formatted on a second thread).

Parameters
----------
lengths : str or os.PathLike
    CSV with header l0..l5 (machine unit).
out : str or os.PathLike
    The output CSV x,y,z,a,b,c,iterations,status (angles in degrees; no pose on a failed row).
    Written whole or not at all.
seed : array_like, shape (6,), optional
    First row's seed x, y, z, a, b, c (degrees); default the machine's home.
from_seed : bool, default False
    Solve every row on its own from the seed.
force : bool, default False
    Replace an existing `out`.

Returns
-------
dict
    rows (solved), failed (rows without a pose).

Raises
------
ValueError
    FILE:LINE for a bad row (nothing is written), or when `out` exists and force is False.)doc";

py::dict fkFile(const Hexapod& h,
                py::handle lengths,
                py::handle out,
                py::handle seed,
                bool from_seed,
                bool force) {
  workflow::HexapodFkFileRequest request;
  request.lengths = pathOf(lengths, "lengths");
  const std::string out_path = pathOf(out, "out");
  if (!seed.is_none()) {
    const DoubleArray a = vectorOf(seed, 6, "seed");
    const double* s = a.data();
    kinematics::PoseRpy pose;
    pose.position = {s[0], s[1], s[2]};
    pose.rpy = {degToRad(s[3]), degToRad(s[4]), degToRad(s[5])};
    request.seed = pose;
  }
  request.from_seed = from_seed;
  workflow::HexapodFkFileSummary summary;
  {
    py::gil_scoped_release release;
    io::AtomicFile file(out_path, force ? io::Overwrite::kAllow : io::Overwrite::kRefuse);
    summary = workflow::solveHexapodFkFile(
        *h.machine, request, [&file](std::string_view text) { file.write(text); });
    file.commit();
  }
  py::dict d;
  d["rows"] = summary.rows;
  d["failed"] = summary.failed;
  return d;
}

}  // namespace

void defHexapodFkFile(py::class_<Hexapod>& cls) {
  cls.def("fk_file",
          &fkFile,
          py::arg("lengths"),
          py::arg("out"),
          py::arg("seed") = py::none(),
          py::arg("from_seed") = false,
          py::arg("force") = false,
          kFkFileDoc);
}

}  // namespace pkm::python
