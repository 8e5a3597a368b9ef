// Every setting of the engine, by module: what a scan, the studio and a settings file set.
// Each field is declared once more in pipeline/settings.cpp (key, range, unit, help), from
// which the CLI flags, the settings files and the studio's forms are made.
#pragma once

#include "common/cuda_runtime.h"
#include "exposure/exposure.h"
#include "imaging/imaging.h"
#include "normalized_radiance/normalized_radiance.h"
#include "pipeline/relocaliser.h"
#include "tracking/tracking.h"
#include "volume/volume.h"

namespace hdrf::pipeline {

struct PipelineOptions {
  volume::VolumeOptions volume;
  tracking::TrackerOptions tracker;
  RelocOptions reloc;
  exposure::ExposureOptions exposure;
  nr::NormalizedRadianceOptions nr;
  imaging::DepthFilterOptions depth;
  int pcf = 1;                   // PCF variant p0..p3 for tracking and fusion (paper: p1 best)
  Device device = Device::kCpu;  // kCuda: the CUDA backend where a GPU is usable, else the CPU
  void Check() const;            // throws SettingError naming the setting
};

}  // namespace hdrf::pipeline
