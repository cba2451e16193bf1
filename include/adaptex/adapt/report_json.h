#pragma once
/// \file report_json.h
/// The one mapping of the library's reports to JSON, used by the CLI (report.json, `--report`,
/// stdout JSON), the Python module (its report dicts) and the studio. Key names, their order and the
/// units are contracts read outside this repository: change them only on purpose. The adaptation's
/// reports: adapt_report.h; the shrink's: shrink_report.h (both included here).
#include <nlohmann/json_fwd.hpp>

#include "adaptex/adapt/adapt_report.h"
#include "adaptex/adapt/shrink_report.h"
#include "adaptex/io/mesh_io.h"
#include "adaptex/paint/eval.h"
#include "adaptex/param/stretch.h"
#include "adaptex/param/unwrap.h"

namespace adaptex {

/// {"components", "genus", "boundary_loops", "charts", "cut_length", "augmentations",
/// "yoshizawa_iterations", "floater_l2", "floater_linf", "final_l2", "final_linf", "coverage",
/// "effective_texel_share", "time": {"cut", "segment", "floater", "yoshizawa", "augment", "pack",
/// "total"}} (times in s).
nlohmann::ordered_json unwrap_report_json(const UnwrapReport& r);
/// What the reader changed: {"dropped_degenerate_faces", "dropped_unreferenced_vertices",
/// "dropped_duplicate_faces", "split_nonmanifold_vertices", "split_pinched_vertices",
/// "flipped_faces", "welded_vertices"}.
nlohmann::ordered_json read_report_json(const ReadReport& r);
/// {"mse", "psnr", "samples", "seed"}.
nlohmann::ordered_json eval_result_json(const EvalResult& r);
/// {"l2", "linf", "area_distortion", "angle_distortion", "flipped", "degenerate"}.
nlohmann::ordered_json stretch_json(const StretchStats& s);

}  // namespace adaptex
