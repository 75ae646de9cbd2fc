// throng-town's on-screen text and occlusion picture (TownOverlay.h).
#include "TownOverlay.h"

#include <cmath>
#include <cstdint>
#include <cstdio>

namespace throng::town {

// The occlusion buffer as a picture: near occluders light, far ones dark, nothing drawn clear. When
// the stage rests, the buffer is the last one built, from another view, and nothing is tested
// against it: it is shown grey and faint, so it is not read as this frame's.
Image occlusionPicture(const OcclusionBuffer& buffer, bool resting) {
    Image image;
    image.name = "occlusion buffer";
    image.width = buffer.width();
    image.height = buffer.height();
    image.rgba.resize(std::size_t(image.width) * std::size_t(image.height) * 4);
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x) {
            const double d = buffer.depthAt(x, image.height - 1 - y);  // buffer row 0 is the bottom
            std::uint8_t* p = &image.rgba[(std::size_t(y) * std::size_t(image.width) + std::size_t(x)) * 4];
            const auto level = static_cast<std::uint8_t>(std::isfinite(d) ? 255.0 / (1.0 + d / 20.0) : 0.0);
            if (resting)
                p[0] = p[1] = p[2] = std::uint8_t(level / 2), p[3] = std::isfinite(d) ? 120 : 60;
            else
                p[0] = p[1] = level, p[2] = std::isfinite(d) ? 255 : 96, p[3] = std::isfinite(d) ? 230 : 140;
        }
    return image;
}

std::string statusText(const sim::Simulation& world, const ActorFrameStatistics& s, const CrowdRenderStatistics& drawn, double drawMs,
                       double fps, double lodScale, bool paused, bool shrunk, bool freeCamera, bool pipelined) {
    char buf[1280];
    std::snprintf(buf, sizeof buf,
                  "%s   %.1f fps   %s processing%s%s\n"
                  "actors %llu: culled with group %llu  A %llu  B %llu  C1 %llu  C2 %llu  C3.1 %llu  C3.2 %llu\n"
                  "posed %llu, skeleton nodes %llu, draw items %llu, triangles %llu\n"
                  "APP+CULL %.2f ms (APP %.2f, refpoints %.2f, bounds %.2f, CULL1 %.2f, roots %.2f, CULL2 %.2f, poses %.2f, CULL3 %.2f, list %.2f)\n"
                  "DRAW %.2f ms: CPU %.2f ms, GPU %.2f ms (town %.2f, meshes %.2f, impostors %.2f, end %.2f; %lld frames behind)\n"
                  "occlusion%s: %llu occluders drawn in %.2f ms; hidden: %llu with their group, %llu Refpoint, %llu Sklsroot, %llu tiles (O: buffer)\n"
                  "key-pose caches: %llu actors in the band, %llu drawn from a cache, %llu skinned (pose did not fit), %llu poses stored\n"
                  "LOD scale %.2f (+/-)   culling pyramid %s (C)   camera %s (Tab)   %s",
                  world.description().name.c_str(), fps, s.processing == Processing::Actor ? "actor" : "traditional",
                  pipelined ? ", DRAW overlapped" : "", paused ? "   PAUSED" : "", (unsigned long long)s.actorsInScene, (unsigned long long)s.culledWithGroup,
                  (unsigned long long)s.a, (unsigned long long)s.b, (unsigned long long)s.c1, (unsigned long long)s.c2,
                  (unsigned long long)s.c3_1, (unsigned long long)s.c3_2, (unsigned long long)s.actorsPosed,
                  (unsigned long long)s.skeletonNodesEvaluated, (unsigned long long)s.drawItems, (unsigned long long)s.primitives,
                  s.appCullMs(), s.appMs, s.refpointMs, s.matricesBoundsMs, s.cullMs, s.skeletonRootMs, s.cull2Ms, s.poseMs,
                  s.cull3Ms, s.drawListMs, drawMs, drawMs - drawn.presentMs, drawn.gpu.totalMs(), drawn.gpu.ms[0], drawn.gpu.ms[1],
                  drawn.gpu.ms[2], drawn.gpu.ms[3], (long long)drawn.gpuFramesBehind, s.occlusionRested ? " (resting: the last test hid little; O shows the last buffer, grey)" : "", (unsigned long long)s.occludersDrawn, s.occlusionBufferMs,
                  (unsigned long long)s.occludedWithGroup, (unsigned long long)s.occludedRefpoint, (unsigned long long)s.occludedSklsroot,
                  (unsigned long long)s.nodesOccluded, (unsigned long long)s.keyPoseBand, (unsigned long long)s.keyPoseActors,
                  (unsigned long long)s.keyPoseMisses, (unsigned long long)s.keyPoseUpdates, lodScale, shrunk ? "shrunk" : "full", freeCamera ? "free" : "path",
                  "W/A/S/D/Q/E move, drag to look, Space pause, P processing, Esc quit");
    return buf;
}

}  // namespace throng::town
