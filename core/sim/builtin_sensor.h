// The default sensor profile compiled into the library: the measured Xtion response and
// noise of resources/sensors/xtion_1406120314.json (MIT, the HDRFusion authors), so the
// synthetic sensor has a real camera's non-gamma response with no file at hand.
#pragma once

#include "radiometry/sensor.h"

namespace hdrf::sim {

// Camera 640x480, fx = fy = 539, depth scale 1000, response and noise as measured.
SensorInfo BuiltinXtionProfile();

}  // namespace hdrf::sim
