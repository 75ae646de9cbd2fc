#pragma once
// What throng-town's window shows over the frame: the statistics text and the occlusion buffer as
// a picture (the O key).

#include <string>

#include "throng/actors/ActorFrameStatistics.h"
#include "throng/render/CrowdRenderer.h"
#include "throng/scenegraph/Image.h"
#include "throng/scenegraph/OcclusionBuffer.h"
#include "throng/sim/Simulation.h"

namespace throng::town {

/// The occlusion buffer as a picture: near occluders light, far ones dark, nothing drawn clear; a
/// resting stage's buffer (the last built, from another view) grey and faint.
Image occlusionPicture(const OcclusionBuffer& buffer, bool resting);

/// The window's status text: frame rate, processing, the cascade's classes, phase times, DRAW on the
/// CPU and the GPU (`drawn`, the last frame drawn, in `drawMs`), occlusion, key-pose caches, and the keys.
std::string statusText(const sim::Simulation& world, const ActorFrameStatistics& s, const CrowdRenderStatistics& drawn, double drawMs,
                       double fps, double lodScale, bool paused, bool shrunk, bool freeCamera, bool pipelined);

}  // namespace throng::town
