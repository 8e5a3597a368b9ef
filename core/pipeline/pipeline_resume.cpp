// Pipeline's resume point: the state a scan saves with its model (resume_point) and takes
// up again on a fresh pipeline (Resume), so a resumed scan goes on exactly as if it had never
// stopped. The frame loop is in pipeline.cpp.
#include <string>

#include "common/error.h"
#include "pipeline/backend.h"
#include "pipeline/pipeline.h"

namespace hdrf::pipeline {

ResumePoint Pipeline::resume_point() const {
  ResumePoint p;
  p.frames = index_;
  p.pose = pose_;
  p.previous_pose = previous_pose_;
  p.first_exposure_ms = first_exposure_ms_;
  p.anchored = anchored_;
  p.recovering = recovering_;
  p.confirmed = confirmed_;
  p.residuals = icp_residuals_;
  p.photo_residuals = photo_residuals_;
  p.lost_run = lost_run_;
  p.exposure_drifts = exposure_drifts_;
  if (keyframe_.valid()) {  // with the entry still being made, as it will be added
    Relocaliser r = reloc_;
    r.Add(keyframe_.get());
    p.reloc = r.entries();
  } else {
    p.reloc = reloc_.entries();
  }
  p.raycast_guide = backend_->RaycastGuide();
  if (!reference_from_model_) {
    p.reference_color = reference_color_.Clone();
    p.reference_depth = reference_depth_.Clone();
  }
  return p;
}

void Pipeline::Resume(const volume::Volume& model, const ResumePoint& p) {
  if (index_ != 0) throw Error("a scan can only be resumed on a fresh pipeline (this one has run " +
                               std::to_string(index_) + " frames)");
  const volume::VolumeOptions& m = model.options();
  const volume::VolumeOptions& v = o_.volume;
  if (m.voxel_m != v.voxel_m || m.truncation_voxels != v.truncation_voxels || m.encoding != v.encoding)
    throw Error("the saved model has " + std::to_string(1000 * m.voxel_m) + " mm voxels, truncation " +
                std::to_string(m.truncation_voxels) + " voxels, " + volume::VoxelEncodingName(m.encoding) +
                " encoding; the settings ask for " + std::to_string(1000 * v.voxel_m) + " mm, " +
                std::to_string(v.truncation_voxels) + ", " + volume::VoxelEncodingName(v.encoding) +
                ": resume with the project's own settings");
  if (p.frames < 0) throw Error("a resume point cannot have a negative frame count");
  if (!p.raycast_guide.empty() && (p.raycast_guide.width() != volume::GuideTiles(cam_.width) ||
                                   p.raycast_guide.height() != volume::GuideTiles(cam_.height)))
    throw Error("the resume point's ray cast guide is " + std::to_string(p.raycast_guide.width()) + "x" +
                std::to_string(p.raycast_guide.height()) + " tiles; the camera needs " +
                std::to_string(volume::GuideTiles(cam_.width)) + "x" + std::to_string(volume::GuideTiles(cam_.height)));
  const bool need_frame = !reference_from_model_ && p.frames > 0;
  if (need_frame && (p.reference_color.width() != cam_.width || p.reference_color.height() != cam_.height ||
                     p.reference_depth.width() != cam_.width || p.reference_depth.height() != cam_.height))
    throw Error("this scan tracks frame to frame, and its resume point has no " + std::to_string(cam_.width) + "x" +
                std::to_string(cam_.height) + " reference frame");
  Backend& b = *backend_;
  b.LoadVolume(model);
  pose_ = p.pose;
  previous_pose_ = p.previous_pose;
  index_ = p.frames;
  first_exposure_ms_ = p.first_exposure_ms;
  full_reported_ = model.full();
  anchored_ = p.anchored;
  recovering_ = p.recovering;
  confirmed_ = p.confirmed;
  icp_residuals_ = p.residuals;
  photo_residuals_ = p.photo_residuals;
  lost_run_ = p.lost_run;
  exposure_drifts_ = p.exposure_drifts;
  reloc_.Restore(p.reloc);
  if (p.frames == 0) return;
  // The state the last Process() left: the ray cast from the last pose, and the reference.
  if (model.allocated_bricks() > 0) {
    // The same ray cast as the scan's last one, from where its rays started.
    b.SetRaycastGuide(p.raycast_guide);
    b.Raycast(pose_, p.raycast_guide.empty() ? Backend::RaycastStart::kNear : Backend::RaycastStart::kKept);
  }
  if (reference_from_model_) {
    if (b.HasRender()) b.ReferenceFromRender(kNoClip);
    ref_clip_ = kNoClip;
    ref_pending_.reset();
  } else {
    b.Convert(p.reference_color, p.reference_depth);
    b.Normalize();
    b.BuildLive();
    b.ReferenceFromLive(pose_);
    reference_color_ = p.reference_color.Clone();
    reference_depth_ = p.reference_depth.Clone();
  }
}

}  // namespace hdrf::pipeline
