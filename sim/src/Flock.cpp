#include "throng/sim/Flock.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "throng/actors/ActorTemplate.h"
#include "throng/actors/SkeletonPose.h"
#include "throng/scenegraph/ThreadTeam.h"
#include "throng/sim/CounterRng.h"

namespace throng::sim {

Flock::Flock(Settings settings, std::vector<double> levelEnds, EffectCounters* counters)
    : settings_(settings), levelEnds_(std::move(levelEnds)), counters_(counters) {
    if (!(settings_.size.x > 0 && settings_.size.y > 0) || !(settings_.neighbourRadius > 0) || !(settings_.speed.x > 0) ||
        settings_.speed.y < settings_.speed.x || settings_.altitude.y < settings_.altitude.x)
        throw std::invalid_argument("Flock: area, neighbour radius and speed range must be positive and ordered");
    if (counters_) counters_->constructed("flight");
}

std::uint32_t Flock::addBird(const Bird& bird) {
    if (started_) throw std::invalid_argument("Flock::addBird: birds must be added before the first frame");
    if (!bird.tmpl) throw std::invalid_argument("Flock::addBird: argument 'bird.tmpl' is null");
    if (bird.flapClip < 0 || std::size_t(bird.flapClip) >= bird.tmpl->clips().size())
        throw std::invalid_argument("Flock::addBird: template '" + bird.tmpl->name() + "' has no clip " + std::to_string(bird.flapClip));
    const CounterRng rng(settings_.seed, bird.stream);
    const glm::dvec3 p(settings_.center.x + (rng.uniform(0) - 0.5) * settings_.size.x,
                       rng.uniform(1, settings_.altitude.x, settings_.altitude.y),
                       settings_.center.y + (rng.uniform(2) - 0.5) * settings_.size.y);
    const double heading = rng.uniform(3, 0.0, 2.0 * std::numbers::pi), speed = rng.uniform(4, settings_.speed.x, settings_.speed.y);
    birds_.push_back(bird);
    pos_.push_back(p);
    vel_.push_back(glm::dvec3(std::sin(heading), 0.0, std::cos(heading)) * speed);
    return static_cast<std::uint32_t>(birds_.size() - 1);
}

void Flock::advance(const FrameContext& context) {
    started_ = true;
    const double dt = context.deltaTime;
    if (dt <= 0.0 || birds_.empty()) return;
    const std::size_t n = birds_.size();
    // Bucket the birds into a grid over the area (counting sort: no allocation once warm).
    const double cell = settings_.neighbourRadius;
    const glm::dvec2 lo = settings_.center - 0.5 * settings_.size - cell;
    const int nx = int(std::ceil((settings_.size.x + 2 * cell) / cell)), nz = int(std::ceil((settings_.size.y + 2 * cell) / cell));
    auto cellOf = [&](const glm::dvec3& p) {
        const int cx = std::clamp(int((p.x - lo.x) / cell), 0, nx - 1), cz = std::clamp(int((p.z - lo.y) / cell), 0, nz - 1);
        return std::uint32_t(cz * nx + cx);
    };
    cellStart_.assign(std::size_t(nx) * nz + 1, 0);
    birdCell_.resize(n);
    for (std::size_t i = 0; i < n; ++i) ++cellStart_[(birdCell_[i] = cellOf(pos_[i])) + 1];
    for (std::size_t c = 1; c < cellStart_.size(); ++c) cellStart_[c] += cellStart_[c - 1];
    cellBirds_.resize(n);
    cellFill_.assign(cellStart_.begin(), cellStart_.end() - 1);
    for (std::uint32_t i = 0; i < n; ++i) cellBirds_[cellFill_[birdCell_[i]]++] = i;  // ids ascend within a cell
    nextPos_.resize(n);
    nextVel_.resize(n);
    const double r2 = settings_.neighbourRadius * settings_.neighbourRadius, sep2 = settings_.separation * settings_.separation;
    // Per bird, in parallel: each reads the last step's positions and writes only its next ones.
    forEachChunk(n, 256, [&](std::size_t, std::size_t begin, std::size_t end) {
        for (auto i = std::uint32_t(begin); i < end; ++i) {
            const glm::dvec3 p = pos_[i], v = vel_[i];
            glm::dvec3 centre(0.0), heading(0.0), away(0.0);
            int neighbours = 0;
            const int cx = int(birdCell_[i] % std::uint32_t(nx)), cz = int(birdCell_[i] / std::uint32_t(nx));
            for (int z = std::max(0, cz - 1); z <= std::min(nz - 1, cz + 1); ++z)
                for (int x = std::max(0, cx - 1); x <= std::min(nx - 1, cx + 1); ++x) {
                    const std::uint32_t c = std::uint32_t(z * nx + x);
                    for (std::uint32_t k = cellStart_[c]; k < cellStart_[c + 1]; ++k) {
                        const std::uint32_t j = cellBirds_[k];
                        if (j == i) continue;
                        const glm::dvec3 d = pos_[j] - p;
                        const double d2 = glm::dot(d, d);
                        if (d2 > r2) continue;
                        centre += pos_[j];
                        heading += vel_[j];
                        if (d2 < sep2 && d2 > 1e-12) away -= d / d2;
                        ++neighbours;
                    }
                }
            glm::dvec3 steer(0.0);
            if (neighbours) {
                steer += 0.6 * (centre / double(neighbours) - p);
                steer += 0.8 * (heading / double(neighbours) - v);
                steer += 6.0 * away;
            }
            // Stay over the area and within the altitude band.
            const glm::dvec2 half = 0.5 * settings_.size;
            if (p.x < settings_.center.x - half.x) steer.x += 4.0;
            if (p.x > settings_.center.x + half.x) steer.x -= 4.0;
            if (p.z < settings_.center.y - half.y) steer.z += 4.0;
            if (p.z > settings_.center.y + half.y) steer.z -= 4.0;
            if (p.y < settings_.altitude.x) steer.y += 3.0;
            if (p.y > settings_.altitude.y) steer.y -= 3.0;
            // A little wander, from the bird's own stream.
            const CounterRng rng(settings_.seed, birds_[i].stream);
            steer += glm::dvec3(rng.uniform(3 * steps_ + 100, -1, 1), 0.3 * rng.uniform(3 * steps_ + 101, -1, 1), rng.uniform(3 * steps_ + 102, -1, 1));
            glm::dvec3 nv = v + steer * dt;
            const double speed = glm::length(nv);
            nv *= std::clamp(speed, settings_.speed.x, settings_.speed.y) / std::max(speed, 1e-9);
            nextVel_[i] = nv;
            nextPos_[i] = p + nv * dt;
        }
    });
    std::swap(pos_, nextPos_);
    std::swap(vel_, nextVel_);
    ++steps_;
    if (counters_) counters_->ticked("flight", n);
}

Mat4 Flock::referencePoint(std::uint32_t slot, const FrameContext&, OpTally* ops) {
    // Facing along the velocity, the body pitched with the climb.
    const glm::dvec3 f = glm::normalize(vel_[slot]);
    const glm::dvec3 side = glm::normalize(glm::cross(glm::dvec3(0, 1, 0), f));
    const glm::dvec3 up = glm::cross(f, side);
    THRONG_TALLY(ops, 24, 14, 2, 2);
    Mat4 m(1.0);
    m[0] = Vec4(side, 0.0);
    m[1] = Vec4(up, 0.0);
    m[2] = Vec4(f, 0.0);
    m[3] = Vec4(pos_[slot], 1.0);
    return m;
}

double Flock::clipTime(std::uint32_t slot, double time) const {
    const Bird& b = birds_[slot];
    const double phase = CounterRng(settings_.seed, b.stream).uniform(5);  // birds do not beat in step
    return time + phase * b.tmpl->clips()[std::size_t(b.flapClip)]->duration();
}

void Flock::pose(std::uint32_t slot, double time, int level, const ActorTemplate& tmpl,
                 std::span<const std::uint8_t> active, std::span<float> dofs, OpTally* ops) {
    if (level >= static_cast<int>(levelEnds_.size())) {  // beyond the last band: rest pose
        writeRestPose(tmpl, active, dofs);
        return;
    }
    const Bird& b = birds_[slot];
    const AnimationClip& flap = *tmpl.clips()[std::size_t(b.flapClip)];
    flap.sample(tmpl, clipTime(slot, time), true, active, dofs, ops, level >= 1);
}

}  // namespace throng::sim
