/// \file tablet.cpp
#include "tablet.h"

#include <cstdlib>
#include <map>
#include <vector>

#ifdef ADAPTEX_STUDIO_XINPUT2
#include <GLFW/glfw3.h>
#define GLFW_EXPOSE_NATIVE_X11
#include <GLFW/glfw3native.h>
#include <X11/Xlib.h>
#include <X11/extensions/XInput2.h>
#endif

namespace adaptex::studio {

#ifdef ADAPTEX_STUDIO_XINPUT2

namespace {
struct Range {
  int number = -1;  // valuator index of the pressure
  double min = 0, max = 1;
};
int g_x_error = 0;
int record_x_error(Display*, XErrorEvent* e) {
  g_x_error = e->error_code;
  return 0;
}
}  // namespace

struct TabletPressure::Impl {
  Display* dpy = nullptr;
  int xi_opcode = 0;
  std::map<int, Range> pressure;  // device id -> its pressure valuator (devices with one)
  std::vector<std::string> names;
  double last = 1;

  void select(unsigned long window) {
    const Atom label = XInternAtom(dpy, "Abs Pressure", False);
    int n = 0;
    XIDeviceInfo* info = XIQueryDevice(dpy, XIAllDevices, &n);
    std::vector<unsigned char> bits(XIMaskLen(XI_LASTEVENT), 0);
    XISetMask(bits.data(), XI_Motion);
    XISetMask(bits.data(), XI_ButtonPress);
    std::vector<XIEventMask> masks;
    for (int k = 0; k < n; ++k) {
      const XIDeviceInfo& d = info[k];
      if (d.use != XISlavePointer && d.use != XIFloatingSlave) continue;
      for (int c = 0; c < d.num_classes; ++c) {
        if (d.classes[c]->type != XIValuatorClass) continue;
        const auto* v = reinterpret_cast<const XIValuatorClassInfo*>(d.classes[c]);
        if (v->label == label && v->max > v->min) {
          pressure[d.deviceid] = Range{v->number, v->min, v->max};
          names.emplace_back(d.name);
        }
      }
      masks.push_back(XIEventMask{d.deviceid, int(bits.size()), bits.data()});
    }
    XIFreeDeviceInfo(info);
    if (masks.empty()) return;
    // Button presses of a device go to one client per window: if another has them, motion only.
    XErrorHandler old = XSetErrorHandler(record_x_error);
    g_x_error = 0;
    XISelectEvents(dpy, Window(window), masks.data(), int(masks.size()));
    XSync(dpy, False);
    if (g_x_error != 0) {
      XIClearMask(bits.data(), XI_ButtonPress);
      XISelectEvents(dpy, Window(window), masks.data(), int(masks.size()));
      XSync(dpy, False);
    }
    XSetErrorHandler(old);
  }

  void read(const XIDeviceEvent& e) {
    const auto it = pressure.find(e.sourceid);
    if (it == pressure.end()) {
      last = 1;  // a mouse
      return;
    }
    const Range& r = it->second;
    last = valuator_pressure(e.valuators.mask, e.valuators.mask_len, e.valuators.values, r.number, r.min, r.max, last);
  }
};

TabletPressure::TabletPressure(GLFWwindow* window) : impl_(std::make_unique<Impl>()) {
  Display* glfw_dpy = glfwGetX11Display();
  const ::Window xid = window ? glfwGetX11Window(window) : 0;
  if (!glfw_dpy || !xid) return;
  impl_->dpy = XOpenDisplay(DisplayString(glfw_dpy));
  if (!impl_->dpy) return;
  int event = 0, error = 0, major = 2, minor = 0;
  if (!XQueryExtension(impl_->dpy, "XInputExtension", &impl_->xi_opcode, &event, &error) ||
      XIQueryVersion(impl_->dpy, &major, &minor) != Success) {
    XCloseDisplay(impl_->dpy);
    impl_->dpy = nullptr;
    return;
  }
  impl_->select(xid);
}

TabletPressure::~TabletPressure() {
  if (impl_->dpy) XCloseDisplay(impl_->dpy);
}

bool TabletPressure::available() const { return impl_->dpy != nullptr; }
int TabletPressure::pens() const { return int(impl_->pressure.size()); }

double TabletPressure::poll() {
  Display* dpy = impl_->dpy;
  if (!dpy) return 1;
  while (XPending(dpy) > 0) {
    XEvent ev;
    XNextEvent(dpy, &ev);
    XGenericEventCookie* cookie = &ev.xcookie;
    if (cookie->type != GenericEvent || cookie->extension != impl_->xi_opcode || !XGetEventData(dpy, cookie)) continue;
    if (cookie->evtype == XI_Motion || cookie->evtype == XI_ButtonPress)
      impl_->read(*static_cast<const XIDeviceEvent*>(cookie->data));
    XFreeEventData(dpy, cookie);
  }
  return impl_->last;
}

std::string TabletPressure::describe() const {
  if (!impl_->dpy) return "no XInput2: pen pressure 1";
  std::string s = std::to_string(impl_->names.size()) + " pointer device(s) with pressure";
  for (size_t k = 0; k < impl_->names.size(); ++k) s += (k ? ", " : ": ") + impl_->names[k];
  return s;
}

#else  // no XInput2: every dab at pressure 1

struct TabletPressure::Impl {};
TabletPressure::TabletPressure(GLFWwindow*) {}
TabletPressure::~TabletPressure() = default;
bool TabletPressure::available() const { return false; }
int TabletPressure::pens() const { return 0; }
double TabletPressure::poll() { return 1; }
std::string TabletPressure::describe() const { return "built without XInput2: pen pressure 1"; }

#endif

std::optional<double> test_pressure_from_env() {
  const char* v = std::getenv("ADAPTEX_STUDIO_TEST_PRESSURE");
  if (!v || !*v) return std::nullopt;
  char* end = nullptr;
  const double p = std::strtod(v, &end);
  if (end == v || *end != '\0' || !(p >= 0 && p <= 1)) return std::nullopt;
  return p;
}

}  // namespace adaptex::studio
