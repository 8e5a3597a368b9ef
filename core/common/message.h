// The engine's messages of normal operation (why a frame was not fused, what a sweep plan
// warns about, why a calibration is marginal, what a profile lacks): each has one fixed
// English wording with numbered arguments ("only %1 % of pixels matched"), listed once in
// HDRF_WORDINGS below. The engine writes them in English (the command-line tools, reports and
// logs); a user interface recognises a message by its wording (ParseMessage), translates the
// wording and puts the arguments back, numbers in the user's notation. Arguments that are
// numbers are written by Num/Sig (C locale); an argument may itself be a message.
#pragma once

#include <initializer_list>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace hdrf {

struct Wording {
  const char* name;     // the constant's name, for tests and tools
  const char* english;  // %1..%9 mark the arguments; each is used once
};

// clang-format off
#define HDRF_WORDINGS(X)                                                                                             \
  /* Tracking and pose verification (a frame's "why"). */                                                            \
  X(kNoCorrespondences, "no correspondences")                                                                        \
  X(kFewPixelsMatched, "only %1 % of pixels matched")                                                                \
  X(kIllConditioned, "ill-conditioned (geometry and texture too poor)")                                              \
  X(kPoseJumped, "pose jumped implausibly far")                                                                      \
  X(kTooFast, "the pose moved %1 m in %2 ms since the last accepted one (%3 m/s, more than %4 m/s)")                 \
  X(kIcpResidualHigh, "point-to-surface error %1 cm, %2x the scan's usual %3 cm")                                    \
  X(kPhotoResidualHigh, "radiance residual %1, %2x the scan's usual %3")                                             \
  X(kFewPixelsFit, "only %1 % of the matched pixels fit the pose")                                                   \
  X(kLeftPrediction, "the pose departs from the predicted motion by %1 cm and %2 degrees, %3x what a hand-held "   \
                     "camera does")                                                                                 \
  X(kTooLittleColour, "recovering, and only %1 % of the matched pixels have usable colour (the rest clipped or dark): "  \
                      "too little to confirm the pose")                                                              \
  X(kExposureDisagrees, "the exposure the pose implies is %1x the sensor's reported exposure (relative to the "      \
                        "scan so far)")                                                                              \
  X(kWaitingForAnchor, "waiting for a frame to anchor the model: %1 % of its pixels have depth, %2 % needed")        \
  X(kConfirmingPose, "confirming the pose after a loss (%1 of %2 frames)")                                           \
  /* Settings the engine had to change, once at the start of a scan. */                                              \
  X(kLevelsLowered, "tracker.levels %1 lowered to %2 for %3x%4 frames (a pyramid level under %5x%6 pixels misleads " \
                    "the tracker)")                                                                                  \
  X(kCudaNotUsable, "CUDA requested but not usable (%1); running on the CPU")                                        \
  /* Sweep planning and capture (the calibration wizard, capture-sweep). */                                          \
  X(kPlanSaturated, "%1 % of the image is saturated even at the shortest exposure (%2 ms): the brightest parts add " \
                    "nothing to the top of the curve")                                                               \
  X(kPlanStepsWidened, "the scene spans %1 stops: steps widened to %2 stops to stay within %3 exposures")            \
  X(kPlanCoverageGap, "the planned sweep covers %1 % of the levels of channel %2 (widest gap: levels %3 to %4): the " \
                      "curve is interpolated there")                                                                 \
  X(kPlanCoverage, "the planned sweep covers %1 % of the levels of channel %2: the curve is interpolated there")     \
  X(kAutoExposureOn, "%1: auto exposure is on (as the camera reports it); the camera would choose its own exposures " \
                     "and the sweep's would not be the ones recorded. Lock auto exposure and try again.")            \
  X(kAutoWhiteBalanceOn, "%1: auto white balance is on (as the camera reports it); it would change the colour "      \
                         "gains between exposures. Lock white balance and try again.")                               \
  X(kExposureIgnored, "%1: the images did not brighten when the exposure was set 2 stops longer (mean level %2 at "  \
                      "%3 ms, %4 at %5 ms); the camera is not taking the exposure it is given (automatic exposure "  \
                      "still acting?). Lock auto exposure and try again.")                                           \
  X(kSaturatedAtShortest, "%1: even at the shortest exposure (%2 ms) %3 % of the image is saturated. Dim the "       \
                          "lights, point the camera at a darker scene or lower its gain, then plan again.")          \
  X(kBlackAtLongest, "%1: even at the longest exposure (%2 ms) %3 % of the image is black. Light the scene, or "     \
                     "point the camera at a brighter one, then plan again.")                                         \
  X(kTooFewExposures, "%1: the camera's exposures (%2 ms to %3 ms) give fewer than 3 distinct exposures; "           \
                      "calibration needs 3 or more")                                                                 \
  X(kCoverageTooLowGap, "%1: the planned sweep covers only %2 % of the levels of channel %3 (widest gap: levels %4 " \
                        "to %5). Point the camera at a scene with dark and bright parts and many shades between "    \
                        "(not a wall or a grey card), then plan again.")                                             \
  X(kCoverageTooLow, "%1: the planned sweep covers only %2 % of the levels of channel %3. Point the camera at a "    \
                     "scene with dark and bright parts and many shades between (not a wall or a grey card), then "   \
                     "plan again.")                                                                                  \
  X(kPlanningCancelled, "planning cancelled")                                                                        \
  X(kMovedBetweenRepeats, "the image changed between repeats (%1 % of image regions changed brightness order): the " \
                          "camera or the scene moved")                                                               \
  X(kFlicker, "the brightness changed by %1 % between repeats: flickering light")                                    \
  X(kMovedSinceBefore, "the image no longer matches the exposure before (%1 % of image regions changed brightness "  \
                       "order): the camera or the scene moved")                                                      \
  X(kRecapturing, "re-capturing %1 ms: %2")                                                                          \
  X(kCaptureFailed, "At %1 ms (step %2 of %3) %4, %5 times in a row. %6 The %7 steps captured so far are kept in "   \
                    "%8.")                                                                                           \
  X(kAdviceFlicker, "Switch off fluorescent or dimmed LED lights (or use daylight), then resume.")                   \
  X(kAdviceMovedAcross, "The camera was moved: put it back exactly where it was, or start a new sweep.")             \
  X(kAdviceKeepStill, "Put the camera on a tripod or a table and keep the scene still, then resume.")                \
  /* The calibration's verdict (reasons for marginal or redo). */                                                    \
  X(kExposuresDisagreeRedo, "%1 of %2 exposures disagree with the merge by more than %3 stops (worst %4 stops at "   \
                            "%5 ms): the exposure times do not match the images, or the scene changed")              \
  X(kExposuresDisagree, "%1 of %2 exposures disagree with the merge by more than %3 stops (worst %4 stops at %5 "    \
                        "ms); good is below %6 stops")                                                               \
  X(kHeldBackFewPixels, "too few well-exposed pixels at %1 ms to check the fit on a held-back exposure")             \
  X(kHeldBackRedo, "the %1 ms exposure, held back, is predicted from the others only within %2 stops (limit %3 "     \
                   "stops): the response does not hold between exposures")                                          \
  X(kHeldBackMarginal, "the %1 ms exposure, held back, is predicted within %2 stops (good below %3 stops)")          \
  X(kHeldBackFailed, "the fit without the %1 ms exposure failed: %2")                                                \
  X(kLevelsUncovered, "%1 % of the %2 levels are covered (levels %3 to %4 not seen): the curve is interpolated "     \
                      "there; a scene with more distinct brightnesses covers them")                                  \
  X(kStepsTooWide, "exposures up to %1 stops apart; steps of a stop or less pin the curve down near saturation")     \
  X(kNoiseMisfit, "the noise level function does not fit the measured noise (rms relative misfit %1, limit %2): "    \
                  "it is not saved")                                                                                 \
  /* Sensors, profiles and sequences. */                                                                             \
  X(kNoDepthRegistration, "device '%1' cannot register depth to colour: depth is used as delivered")                 \
  X(kRecordingProfileMissing, "%1 is missing: the built-in Asus Xtion profile is assumed")                           \
  X(kRecordingExposuresMissing, "%1 is missing: every frame is of unknown exposure")                                 \
  X(kNoProfileSerial, "no profile for device '%1' (serial %2) in %3: using the built-in Asus Xtion profile. Its "    \
                      "response and intrinsics are not this device's own; calibrate it with "                        \
                      "hdrfusion-calibration-wizard (or hdrfusion capture-sweep, then hdrfusion calibrate "          \
                      "--save-profile), which stores its profile as %4")                                                           \
  X(kNoProfile, "no profile for device '%1' in %2: using the built-in Asus Xtion profile. Its response and "         \
                "intrinsics are not this device's own; calibrate it with hdrfusion-calibration-wizard (or "          \
                "hdrfusion capture-sweep, then hdrfusion calibrate --save-profile), which stores its profile as %3")               \
  X(kNoExposureUnit, "the profile gives no exposure unit for this device ('hdrfusion.device.exposure_ms_per_unit'): " \
                     "frames are recorded as of unknown exposure and the engine estimates exposure ratios itself")   \
  X(kForeignSyntheticKeys, "%1: the 'synthetic' block is not this project's (it holds other keys); ignored")         \
  X(kForeignSyntheticValue, "%1: the 'synthetic' block is not this project's (it holds no object); ignored")         \
  X(kSrgbAssumed, "%1 has no 'response' calibration: the sRGB curve is assumed, so the HDR radiance is only as "     \
                  "good as that guess")                                                                              \
  /* Scan jobs. */                                                                                                    \
  X(kRecoveryPruned, "removed %1 recovery files of earlier unfinished scans (%2 MiB) from %3: older than %4 days, or " \
                     "beyond the newest %5 and %6 GiB")                                                               \
  /* Asset export. */                                                                                                \
  X(kNoKeyframes, "the scan has no keyframes: the texture holds the volume's radiance only (as sharp as the voxels)")
// clang-format on

namespace words {
#define HDRF_DECLARE_WORDING(id, text) inline constexpr Wording id{#id, text};
HDRF_WORDINGS(HDRF_DECLARE_WORDING)
#undef HDRF_DECLARE_WORDING
}  // namespace words

// Every wording, in the order listed.
const std::vector<const Wording*>& AllWordings();

// The English message: `w` with %N replaced by args[N-1]. Throws std::logic_error when the
// number of arguments does not match the wording (a programming error).
std::string Say(const Wording& w, std::initializer_list<std::string> args = {});

// Numbers as arguments, in the C locale: `decimals` fixed decimals, or `digits` significant
// digits (printf's %g); whole numbers as std::to_string.
std::string Num(double v, int decimals);
std::string Sig(double v, int digits = 4);

// A message recognised by its wording: which wording, and its arguments in order (%1 first).
struct ParsedMessage {
  const Wording* wording = nullptr;
  std::vector<std::string> args;
};
// The wording `text` was said with, or nothing when it matches none. Where two wordings fit,
// the one with more fixed text wins.
std::optional<ParsedMessage> ParseMessage(std::string_view text);

}  // namespace hdrf
