#pragma once
/// \file tablet.h
/// Pen pressure for the studio's brush. GLFW reports no pressure, so on X11 a second connection to
/// the display reads XInput2 motion and button events of the slave pointer devices over the studio's
/// window (slave events do not take core events away from GLFW) and keeps the "Abs Pressure"
/// valuator of the device that moved last, normalised by its range. A device without pressure (a
/// mouse) gives 1. Elsewhere (no X11 / XInput2) the pressure is always 1 (docs/studio.md, "Pen
/// pressure").
#include <memory>
#include <optional>
#include <string>

struct GLFWwindow;

namespace adaptex::studio {

class TabletPressure {
 public:
  /// Listens to the pointer devices over GLFW window \p window (on its X11 display, through a
  /// connection of its own). Without X11, XInput2 2.0 or a display, available() is false.
  explicit TabletPressure(GLFWwindow* window);
  ~TabletPressure();
  TabletPressure(const TabletPressure&) = delete;
  TabletPressure& operator=(const TabletPressure&) = delete;

  bool available() const;
  /// The number of pointer devices with a pressure valuator (pens, erasers, touch pads).
  int pens() const;
  /// Reads the events that arrived; \return the pressure of the device that moved or pressed last,
  /// in [0,1] (1: a device without pressure, or no event yet).
  double poll();
  /// What was found, for the log ("2 pens: Wacom Intuos Pen stylus, ...").
  std::string describe() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// The pressure valuator \p number of an XInput2 event, normalised from [\p min, \p max] to [0,1]:
/// the event lists the values of the valuators set in \p mask (\p mask_len bytes, bit k = valuator k)
/// packed in order. \return the pressure, or \p previous when the event does not carry it (unchanged).
inline double valuator_pressure(const unsigned char* mask, int mask_len, const double* values, int number, double min,
                                double max, double previous) {
  const auto set = [&](int k) { return (mask[k >> 3] & (1 << (k & 7))) != 0; };
  if (number < 0 || number >= mask_len * 8 || !set(number) || !(max > min)) return previous;
  int slot = 0;  // the index among the set bits
  for (int k = 0; k < number; ++k) slot += set(k) ? 1 : 0;
  const double p = (values[slot] - min) / (max - min);
  return p < 0 ? 0 : p > 1 ? 1 : p;
}

/// The pressure from the test hook ADAPTEX_STUDIO_TEST_PRESSURE (a number in [0,1]: every dab is
/// painted at it, as a pen held at that pressure would), or nothing. \throw none (a bad value: nothing)
std::optional<double> test_pressure_from_env();

}  // namespace adaptex::studio
