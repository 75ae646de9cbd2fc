// Rank 0's run of throng-town (TownRun.h): drawing set up, frames prepared and drawn, headless or in
// a window, and the files a run leaves.

#include "TownRun.h"

#include <GLFW/glfw3.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <numbers>
#include <optional>

#include "RankPosing.h"
#include "TownOverlay.h"
#include "throng/render/ContextFactory.h"
#include "throng/render/GlfwWindowContext.h"
#include "throng/render/ImageIO.h"
#include "throng/scenegraph/OcclusionCulling.h"
#include "throng/scenegraph/Stopwatch.h"
#include "throng/sim/BudgetLadder.h"
#include "throng/sim/Locomotion.h"
#include "throng/support/ProgressBar.h"
#include "throng/support/SceneImpostors.h"
#include "throng/support/StopSignals.h"
#include "throng/scenegraph/WholeFile.h"

namespace throng::town {

namespace fs = std::filesystem;

TownRun::TownRun(const TownOptions& o, sim::Simulation& world, sim::Ranks& ranks, std::unique_ptr<sim::FrameBudgetAllocator> budget,
                 std::unique_ptr<CrowdRecording> recorder)
    : o_(o), world_(world), ranks_(ranks), budget_(std::move(budget)), recorder_(std::move(recorder)),
      distributed_(sim::Ranks::launchedByMpi()), pipeline_(o.pipeline) {
    std::string why;
    const bool posing = o.poseOnRanks && distributed_;
    const bool wantWindow = !o.headless && (o.gl == "auto" || o.gl == "window") && displayAvailable() && ranks.size() == 1 && !posing;
    if (!o.headless && ranks.size() > 1) std::fprintf(stderr, "throng-town: %d ranks run headless\n", ranks.size());
    context_ = createContext({.width = o.width, .height = o.height, .window = wantWindow, .title = "Throng town", .api = glApiFromName(o.gl)},
                             &why);
    window_ = !context_->headless();
    if (wantWindow && !window_) std::fprintf(stderr, "throng-town: no window (%s): running headless\n", why.c_str());
    std::fprintf(stderr, "throng-town: GL: %s; %s\n", context_->description().c_str(), context_->vendor().c_str());
    lodScale_ = o.lodScale > 0.0 ? o.lodScale : world.description().representation.lodScale;
    world.setThreads(unsigned(o.threads));
    processor_ = std::make_unique<ActorProcessor>(world.crowd());
    ActorProcessor& processor = *processor_;
    processor.setProcessing(o.processing == "traditional" ? Processing::Traditional : Processing::Actor);
    processor.setThreads(unsigned(o.threads));
    processor.setLodScale(lodScale_);
    townLodScale_ = world.townLodScale();
    // Occlusion culling when the scene declares it (and --occlusion does not turn it off).
    if (o.occlusion && world.description().representation.occlusion) processor.setOcclusion(world.description().representation.occlusion);
    // Key-pose caches for the middle band when the scene declares them (and --key-pose-cache does
    // not turn them off).
    if (o.keyPoseCache) world.attachKeyPoseCaches(processor);
    // Far actors as impostors when the scene asks for them (or --impostor-distance does, or a rung
    // of the --frame-budget ladder).
    double impostorDistance = o.impostorDistance >= 0.0 ? o.impostorDistance : world.description().representation.impostorDistance;
    if (budget_) {
        impostorDistance = 0.0;
        for (const sim::BudgetRung& r : budget_->ladder()) impostorDistance = std::max(impostorDistance, r.settings.impostorDistance);
    }
    if (impostorDistance > 0.0) {
        impostors_ = support::bakeSceneImpostors(context_, world, true);
        impostors_->attach(processor, impostorDistance, world.description().representation.hysteresis * impostorDistance);
    }
    CrowdRendererOptions rendererOptions;
    rendererOptions.impostors.morphBudget = budget_ ? budget_->ladder()[std::size_t(budget_->rung())].settings.morphBudget : o.morphBudget;
    rendererOptions.renderScale = float(budget_ ? budget_->ladder()[std::size_t(budget_->rung())].settings.renderScale : o.renderScale);
    rendererOptions.impostors.source = o.morph == "gl" ? MorphSource::Gpu : MorphSource::Cpu;
    rendererOptions.impostors.gridStep = o.morph == "grid" || o.morph == "background" ? 4 : 1;
    rendererOptions.impostors.backgroundMorph = o.morph == "background";
    rendererOptions.impostors.warp = o.cellWarp == "lines" ? CellWarp::FeatureLines : CellWarp::SurfaceProxy;
    rendererOptions.views.nearest = world.description().representation.impostorViews == sim::ImpostorViews::Nearest;
    rendererOptions.views.warped = world.description().representation.impostorViews == sim::ImpostorViews::Warped;
    rendererOptions.views.smoothstep = world.description().representation.impostorSmoothstep;
    renderer_ = std::make_unique<CrowdRenderer>(context_, rendererOptions);
    if (impostors_) {  // the atlases on the GPU before the first frame, not during it
        std::vector<std::shared_ptr<const ImpostorDrawable>> drawables;
        for (std::size_t i = 0; i < impostors_->size(); ++i) drawables.push_back(impostors_->drawable(i));
        renderer_->preloadImpostors(drawables);
    }
    aspect_ = double(o.width) / double(o.height);
    fs::create_directories(o.out);
    csv_ = std::make_unique<LineFile>(fs::path(o.out) / "stats.csv");
    csv_->append(csvHeader(distributed_ ? ranks.size() : 0, budget_ != nullptr, o.poseOnRanks && distributed_));
    nextRung_ = budget_ ? budget_->rung() : -1;
    rungFrames_.assign(budget_ ? budget_->ladder().size() : 0, 0);
    caches_ = !processor.keyPoseCaches().empty();
    hysteresis_ = world.description().representation.hysteresis;
    for (const auto& layer : world.faceLayers())
        for (ActorId id = 0; id < world.crowd().size(); ++id)
            if (world.crowd().state().behaviour[id] == layer.get())
                faceActors_.push_back({id, layer.get(), world.crowd().state().slot[id]});
    // Ranks posing their own walkers: rank 0's orders sent from within its CULL, shares merged after.
    if (posing) posing_ = std::make_unique<PosingRoot>(world, ranks, processor, aspect_);
    start_ = std::chrono::steady_clock::now();
    // The other ranks wait for rank 0's set-up (impostors, GL) before the first step; posing, they
    // learn with it what rank 0 draws with.
    if (ranks.size() > 1) ranks.broadcast(posing_ ? posing_->setup() : sim::Bytes{}, kStartTag, "start");
}

TownRun::~TownRun() = default;

void TownRun::applyRung(int rung) {
    if (rung == appliedRung_) return;
    const sim::BudgetSettings& b = budget_->ladder()[std::size_t(rung)].settings;
    processor_->setLodScale(b.lodScale);
    world_.setTownLodScale(b.townLodScale > 0.0 ? b.townLodScale : townLodScale_);
    if (impostors_) processor_->setImpostorDistance(b.impostorDistance, hysteresis_ * b.impostorDistance);
    if (caches_) processor_->setKeyPoseDistance(b.keyPoseDistance, hysteresis_ * b.keyPoseDistance);
    appliedRung_ = rung;
}

// Step the simulation (unless paused), then APP and CULL for `camera`.
void TownRun::prepare(PreparedFrame& f, std::int64_t number, const Camera& camera, bool step, double cameraTime) {
    f.number = number;
    f.rung = nextRung_;
    if (budget_) applyRung(f.rung);
    f.stepMs = 0.0;
    f.ghosts = f.handovers = f.deferred = 0;
    f.ranks.assign(distributed_ ? std::size_t(ranks_.size()) : 0, {});
    if (step) {
        // Distributed, the other ranks send only the walkers near this frame's view (a recorder of
        // every actor needs them all, and traditional processing, which culls no actor before it
        // reads its state, does too).
        const bool all = recorder_ || o_.gather == "all" || o_.processing == "traditional";
        if (distributed_) world_.setGatherView(all ? std::nullopt : std::optional<Frustum>(camera.frustum()));
        world_.step();
        f.stepMs = world_.lastStepMs();
        if (const sim::Locomotion* walk = world_.locomotion()) {
            f.ghosts = walk->lastGhostCount(), f.handovers = walk->lastHandoverCount(), f.deferred = walk->lastDeferredCount();
            if (!walk->rankSteps().empty()) f.ranks.assign(walk->rankSteps().begin(), walk->rankSteps().end());
        }
    }
    f.time = world_.now().time;
    f.camera = camera;
    if (posing_) posing_->beginFrame(number, cameraTime);
    f.stats = processor_->processFrame(world_.root(), camera, f.time);
    f.list = &processor_->drawList();
    const FaceTally::Counts faces = faces_.take(world_);
    if (posing_) {
        posing_->finishFrame(f, faces);  // every rank's share: f.list, f.stats and the faces' counts the whole frame's
    } else {
        for (int k = 0; k < 3; ++k) f.faceEvaluations[k] = faces.evaluations[k];
        f.faceMs = 1000.0 * faces.seconds;
    }
    placeCaptions(f, camera);
    if (recorder_) try {
        recorder_->record(world_.crowd(), *processor_);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "\nthrong-town: --vtk: %s; recording stops\n", e.what());
        recorder_.reset();  // finishes what was written
    }
    f.occlusion = showOcclusion_ && processor_->occlusion() ? occlusionPicture(processor_->occlusion()->buffer(), f.stats.occlusionRested) : Image{};
}

// The captions of the speakers within the phrase effect's first band.
void TownRun::placeCaptions(PreparedFrame& f, const Camera& camera) {
    f.captions.clear();
    if (faceActors_.empty()) return;
    // Captions for speakers drawn as meshes this frame: near, in view and not occluded.
    // Each such speaker's highest point as drawn (the top of its parts' spheres) is where its
    // caption stands.
    drawnAsMesh_.assign(world_.crowd().size(), 0);
    captionAt_.resize(world_.crowd().size());
    for (const FaceActor& a : faceActors_) drawnAsMesh_[a.id] = 1;  // 1: has a face; 2: drawn
    for (const DrawItem& item : f.list->items()) {
        if (item.actor == kNoActor || item.representation == Representation::Impostor || !drawnAsMesh_[item.actor]) continue;
        // Part spheres are loose (they hold every shape a morph can make): a little above the
        // highest part's centre rather than its sphere's top.
        const BoundingSphere b = item.drawable->localBound().transformed(item.world.toMat4());
        const Vec3 top = b.center() + Vec3(0.0, 0.5 * b.radius(), 0.0);
        Vec3& at = captionAt_[item.actor];
        if (drawnAsMesh_[item.actor] == 1 || top.y > at.y) at = top;
        drawnAsMesh_[item.actor] = 2;
    }
    for (const FaceActor& a : faceActors_) {
        if (drawnAsMesh_[a.id] != 2) continue;
        const sim::FaceLayer::Settings& settings = a.layer->settings();
        if (!settings.phrase || settings.phrases.empty()) continue;
        const Vec3 at = captionAt_[a.id];
        if (glm::length(at - camera.eye()) > settings.phraseLevels[0] * lodScale_) continue;
        const sim::FaceLayer::Speech speech = a.layer->speechAt(a.slot, f.time);
        if (speech.phrase < 0) continue;
        f.captions.push_back({at, settings.phrases[std::size_t(speech.phrase)]});
    }
}

// DRAW from the prepared frame's own data, then its statistics.
void TownRun::draw(const PreparedFrame& f, const std::function<void()>& beforePresent) {
    if (budget_) {
        const sim::BudgetSettings& b = budget_->ladder()[std::size_t(f.rung)].settings;
        renderer_->setMorphBudget(b.morphBudget);
        renderer_->setRenderScale(float(b.renderScale));
    }
    Stopwatch watch;
    renderer_->beginFrame(f.camera);
    renderer_->setOverlayImage(f.occlusion);
    renderer_->setCaptions(f.captions);
    renderer_->draw(*f.list);
    renderer_->finishImage();  // saved frames show the captions as the window does
    if (beforePresent) beforePresent();
    renderer_->endFrame();
    const double drawMs = watch.elapsedMs();
    lastDrawMs_ = drawMs;
    const double now = seconds();
    sums_.add(f, drawMs, renderer_->statistics());
    csv_->append(csvRow(f, drawMs, 1000.0 * (now - lastFrameEnd_), renderer_->statistics(), budget_.get()));
    if (budget_) {
        drawnRung_ = f.rung;
        drawnCost_ = f.stats.appCullMs() + drawMs;
        ++rungFrames_[std::size_t(f.rung)];
        if (drawnCost_ <= budget_->options().budgetMs) ++framesWithin_;
    }
    lastFrameEnd_ = now;
}

// After a frame's DRAW (both stages of the pipeline joined): the allocator learns its cost and
// picks the rung of the next frame prepared.
void TownRun::allocate() {
    if (budget_ && drawnRung_ >= 0) nextRung_ = budget_->observe(drawnRung_, drawnCost_);
}

void TownRun::runHeadless() {
    support::ProgressBar bar("running", std::size_t(o_.frames));
    if (o_.every > 0) fs::create_directories(fs::path(o_.out) / "frames");
    auto cameraAt = [&](double time) { return world_.camera().at(time, aspect_); };
    // Frame f's camera follows the path at frame f's time, known before it is stepped.
    const double step = world_.description().step;
    prepare(prepared_[0], 0, cameraAt(0.0), true, 0.0);
    for (std::int64_t f = 0; f < o_.frames; ++f) {
        PreparedFrame& current = prepared_[f % 2];
        PreparedFrame& next = prepared_[(f + 1) % 2];
        pipeline_.run([&] { if (f + 1 < o_.frames) prepare(next, f + 1, cameraAt(double(f + 1) * step), true, double(f + 1) * step); },
                      [&] {
                          draw(current, [&] {
                              if (o_.every > 0 && f % o_.every == 0) {  // frame f: its own state, whatever the pipeline
                                  char name[64];
                                  std::snprintf(name, sizeof name, "frame_%06lld.png", (long long)f);
                                  writePng(renderer_->readFrame(), (fs::path(o_.out) / "frames" / name).string());
                              }
                          });
                      });
        allocate();
        if (f == 0) firstFrame_ = seconds();
        char detail[128];
        std::snprintf(detail, sizeof detail, "frame %lld/%lld, %.1f fps", (long long)f + 1, (long long)o_.frames,
                      f > 0 ? double(f) / std::max(1e-9, seconds() - firstFrame_) : 0.0);
        bar.update(std::size_t(f + 1), detail);
        if (const int signal = support::StopSignals::received(); signal && f + 1 < o_.frames) {
            stoppedBy_ = signal;  // frame f is drawn and recorded; the one prepared after it is dropped
            bar.stop(std::size_t(f + 1), "stopped at frame " + std::to_string(f + 1));
            return;
        }
    }
    bar.finish();
}

void TownRun::runWindowed() {
    auto* glfw = static_cast<GlfwWindowContext*>(context_.get())->window();
    ActorProcessor& processor = *processor_;
    bool paused = false, shrunk = false, freeCamera = false;
    double scale = lodScale_, yaw = 0.0, pitch = -0.3, lastX = 0.0, lastY = 0.0;
    glm::dvec3 position(0.0, 30.0, 60.0);
    std::map<int, bool> held;
    auto pressed = [&](int key) {  // once per press
        const bool down = glfwGetKey(glfw, key) == GLFW_PRESS;
        const bool edge = down && !held[key];
        held[key] = down;
        return edge;
    };
    // The camera of the next frame, from the keyboard and mouse (main thread only).
    auto nextCamera = [&](double time) {
        Camera camera = world_.camera().at(time, aspect_);
        if (pressed(GLFW_KEY_TAB)) {
            freeCamera = !freeCamera;
            if (freeCamera) {  // start from where the path camera is
                position = camera.eye();
                const glm::dvec3 f = -glm::dvec3(glm::transpose(glm::dmat3(camera.view()))[2]);
                yaw = std::atan2(f.x, -f.z);
                pitch = std::asin(std::clamp(f.y, -1.0, 1.0));
            }
        }
        double x, y;
        glfwGetCursorPos(glfw, &x, &y);
        if (glfwGetMouseButton(glfw, GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS && freeCamera) {
            yaw += (x - lastX) * 0.004;
            pitch = std::clamp(pitch - (y - lastY) * 0.004, -1.5, 1.5);
        }
        lastX = x, lastY = y;
        if (freeCamera) {
            const glm::dvec3 forward(std::sin(yaw) * std::cos(pitch), std::sin(pitch), -std::cos(yaw) * std::cos(pitch));
            const glm::dvec3 right = glm::normalize(glm::cross(forward, glm::dvec3(0, 1, 0)));
            const double speed = glfwGetKey(glfw, GLFW_KEY_LEFT_SHIFT) == GLFW_PRESS ? 3.0 : 0.6;
            if (glfwGetKey(glfw, GLFW_KEY_W) == GLFW_PRESS) position += forward * speed;
            if (glfwGetKey(glfw, GLFW_KEY_S) == GLFW_PRESS) position -= forward * speed;
            if (glfwGetKey(glfw, GLFW_KEY_D) == GLFW_PRESS) position += right * speed;
            if (glfwGetKey(glfw, GLFW_KEY_A) == GLFW_PRESS) position -= right * speed;
            if (glfwGetKey(glfw, GLFW_KEY_E) == GLFW_PRESS) position.y += speed;
            if (glfwGetKey(glfw, GLFW_KEY_Q) == GLFW_PRESS) position.y -= speed;
            camera.setLookAt(position, position + forward, glm::dvec3(0, 1, 0));
        }
        // The shrunken pyramid culls as if the view were 60% as wide: actors vanish near the edges.
        if (shrunk) {
            Camera narrow = camera;
            const auto& d = world_.description().camera;
            narrow.setPerspective(0.6 * d.fovDegrees * std::numbers::pi / 180.0, aspect_, d.nearDistance, d.farDistance);
            processor.setCullingFrustum(narrow.frustum());
        } else {
            processor.setCullingFrustum(std::nullopt);
        }
        return camera;
    };
    const double step = world_.description().step;
    auto last = std::chrono::steady_clock::now();
    double fps = 0.0;
    prepare(prepared_[0], 0, nextCamera(0.0), true);
    for (std::int64_t f = 0; !context_->shouldClose() && !(o_.framesGiven && f >= o_.frames); ++f) {
        context_->pollEvents();
        if (glfwGetKey(glfw, GLFW_KEY_ESCAPE) == GLFW_PRESS) break;
        if (pressed(GLFW_KEY_SPACE)) paused = !paused;
        if (pressed(GLFW_KEY_C)) shrunk = !shrunk;
        if (pressed(GLFW_KEY_O)) showOcclusion_ = !showOcclusion_;
        if (pressed(GLFW_KEY_P)) processor.setProcessing(processor.processing() == Processing::Actor ? Processing::Traditional : Processing::Actor);
        if (pressed(GLFW_KEY_EQUAL) || pressed(GLFW_KEY_KP_ADD)) processor.setLodScale(scale *= 1.25);
        if (pressed(GLFW_KEY_MINUS) || pressed(GLFW_KEY_KP_SUBTRACT)) processor.setLodScale(scale /= 1.25);
        PreparedFrame& current = prepared_[f % 2];
        PreparedFrame& next = prepared_[(f + 1) % 2];
        const bool advance = !paused;
        const Camera camera = nextCamera(world_.now().time + (advance ? step : 0.0));
        renderer_->setOverlayText(
            statusText(world_, current.stats, renderer_->statistics(), lastDrawMs_, fps, scale, paused, shrunk, freeCamera, o_.pipeline));
        pipeline_.run([&] { prepare(next, f + 1, camera, advance); }, [&] { draw(current, {}); });
        allocate();
        const auto now = std::chrono::steady_clock::now();
        const double dt = std::chrono::duration<double>(now - last).count();
        last = now;
        fps = fps == 0.0 ? 1.0 / std::max(dt, 1e-6) : 0.9 * fps + 0.1 / std::max(dt, 1e-6);
        if ((stoppedBy_ = support::StopSignals::received())) break;
    }
}

void TownRun::finish(const std::string& error) {
    const double wall = seconds();
    if (recorder_) try {
        recorder_->finish();
    } catch (const std::exception& e) {
        std::fprintf(stderr, "throng-town: --vtk: %s\n", e.what());
    }
    nlohmann::json summary = summaryJson(o_, world_, sums_, wall, firstFrame_, ranks_.size());
    if (budget_) {
        nlohmann::json& b = summary["frameBudget"];
        b["budgetMs"] = o_.frameBudget;
        b["ladder"] = o_.frameBudgetLadder;
        b["measure"] = "app_cull_draw_ms: APP+CULL plus DRAW of the same frame, each timed on its own thread";
        b["framesWithinBudget"] = framesWithin_;
        b["shareWithinBudget"] = double(framesWithin_) / double(std::max<std::int64_t>(sums_.frames, 1));
        b["rungChanges"] = budget_->changes();
        for (std::size_t r = 0; r < rungFrames_.size(); ++r) {
            const sim::BudgetRung& rung = budget_->ladder()[r];
            b["rungs"].push_back({{"rung", r}, {"settings", sim::budgetRungValue(rung.settings)}, {"frames", rungFrames_[r]},
                                  {"ladderMs", rung.ms}, {"ladderPixelsOff8", rung.error}, {"measuredMs", budget_->measuredMs(int(r))}});
        }
        std::fprintf(stderr, "throng-town: APP+CULL+DRAW within %.1f ms on %.1f %% of frames\n", o_.frameBudget,
                     100.0 * double(framesWithin_) / double(std::max<std::int64_t>(sums_.frames, 1)));
    }
    summary["gl"] = {{"option", o_.gl}, {"context", context_->kind()}, {"vendor", context_->vendor()},
                     {"renderer", context_->renderer()}, {"version", context_->version()}};
    // Whether the run did all it was asked, and if not, what stopped it (the frames done are "frames").
    summary["completed"] = error.empty() && stoppedBy_ == 0;
    if (stoppedBy_) summary["stoppedBy"] = support::StopSignals::name(stoppedBy_);
    if (!error.empty()) summary["error"] = error;
    writeWholeFile(fs::path(o_.out) / "summary.json", summary.dump(2) + '\n');
    const std::string files = std::string("stats.csv, summary.json") + (!window_ && o_.every > 0 ? " and frames/" : "") + " in " + o_.out;
    if (stoppedBy_)
        std::fprintf(stderr, "throng-town: stopped by %s after %lld of %lld frames; %s\n", support::StopSignals::name(stoppedBy_).c_str(),
                     (long long)sums_.frames, (long long)o_.frames, files.c_str());
    else if (!error.empty())
        std::fprintf(stderr, "throng-town: %lld frames done before the error; %s\n", (long long)sums_.frames, files.c_str());
    else
        std::fprintf(stderr, "throng-town: %lld frames in %.1f s; %s\n", (long long)sums_.frames, wall, files.c_str());
}

}  // namespace throng::town
