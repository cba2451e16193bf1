#pragma once
/// \file session_options.h
/// Option strings of `adaptex paint` (and of the quality bench, which takes the same strings) turned
/// into PaintSessionOptions. String parsing belongs to the command line, not to the library:
/// the library takes enums and numbers.
#include <filesystem>
#include <string>
#include <vector>

#include "adaptex/adapt/session.h"

namespace adaptex::cli {

/// Parses the text of `--grid`: "FINE" or "COARSE,FINE" (e.g. "16,256"), decimal digits, each in
/// [2, 4096], COARSE <= FINE.
/// \throw InvalidInputError one line naming --grid and the text
std::vector<int> parse_grid(const std::string& text);
/// Sets the relaxation grid sizes of \p o from \p grid: {} keeps the defaults, {FINE} or
/// {COARSE, FINE}. \throw InvalidInputError more than two sizes, or a size outside [1, 4096]
void set_grid(AdaptOptions& o, const std::vector<int>& grid);

/// Parses "each-stroke" (or "each_stroke") / "end". \throw InvalidInputError any other string
ReparamSchedule parse_reparam_schedule(const std::string& name);
/// Parses "replay" / "resample". \throw InvalidInputError any other string
TextureUpdate parse_texture_update(const std::string& name);

/// The names of the registered adaptation methods (adapt/method.h), `none` first unless left out.
std::vector<std::string> adapt_method_names(bool with_none = true);
/// "NAME (description) | ..." of the registered methods, for the help of `--adapt`.
std::string adapt_methods_help(bool with_none = true);

/// Session options from the command-line strings of `adaptex paint`:
/// mode as parse_adapt_mode ("none" | "single" | "two-stage" | "density-flow"); grid {} (defaults),
/// {FINE} or {COARSE, FINE}, each in [1, 4096]; alpha/beta < 0 = default, must be finite;
/// reparam "each-stroke" | "end"; update "replay" | "resample"; debug_maps empty = none.
/// \throw InvalidInputError one-line message naming the bad option
PaintSessionOptions make_session_options(int size, int padding, const std::string& mode,
                                         const std::vector<int>& grid, double alpha, double beta,
                                         const std::string& reparam, const std::string& update,
                                         const std::filesystem::path& debug_maps = {});

}  // namespace adaptex::cli
