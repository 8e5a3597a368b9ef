# The modules of core/ and the modules each may include from (besides itself): the engine's
# layering, checked on every build by cmake/CheckLayering.cmake, so that an include that
# goes the wrong way (volume including pipeline, say) fails the build with the file and line.
# Lower layers first. A new module, or a new use between modules, is added here on purpose.
set(HDRF_LAYER_common "")
set(HDRF_LAYER_radiometry common)
set(HDRF_LAYER_tonemap common)
set(HDRF_LAYER_volume common)
set(HDRF_LAYER_normalized_radiance common)
set(HDRF_LAYER_imaging common radiometry)
set(HDRF_LAYER_tracking common imaging)
set(HDRF_LAYER_exposure common tracking)  # the GPU estimator takes the tracker's device pose
set(HDRF_LAYER_mesh common volume)
set(HDRF_LAYER_sim common radiometry)
set(HDRF_LAYER_eval common mesh radiometry sim)
# The per-frame system. (sim: the synthetic sensor as a frame source, pipeline/frame_source.h.)
set(HDRF_LAYER_pipeline common exposure imaging mesh normalized_radiance radiometry sim tracking volume)
# Above the engine: file formats, sensors, and the jobs the programs run.
set(HDRF_LAYER_io common mesh pipeline radiometry tonemap volume)
set(HDRF_LAYER_sensors common io pipeline radiometry sim)
set(HDRF_LAYER_jobs common io pipeline tonemap)
