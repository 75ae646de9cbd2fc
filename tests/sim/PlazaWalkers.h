#pragma once
// A plaza of 60 m (with a pillar in its middle if asked) and walkers spread over it at random, as
// the region, rank and locomotion tests step them.

#include <memory>

#include "throng/actors/SeedHumanoid.h"
#include "throng/sim/CounterRng.h"
#include "throng/sim/Locomotion.h"
#include "throng/sim/NavMesh.h"

namespace throng::sim::test {

/// The plaza's navigation mesh: 60 x 60 m around the origin, with an 8 m pillar when `pillar`.
inline std::shared_ptr<const NavMesh> plaza(bool pillar) {
    NavGeometry g;
    g.addBox(glm::vec3(-30, -0.5f, -30), glm::vec3(30, 0, 30), true);
    if (pillar) g.addBox(glm::vec3(-4, 0, -4), glm::vec3(4, 6, 4), false);
    return NavMesh::build(g);
}

/// `count` seed humanoids walking on `nav` with `settings`, starting at random points drawn from
/// stream `seed`; with `varySpeed` their speeds spread over 1 to 1.6 m/s (1.4 m/s otherwise).
inline std::shared_ptr<Locomotion> plazaWalkers(const std::shared_ptr<const NavMesh>& nav, const Locomotion::Settings& settings,
                                                int count, std::uint64_t seed, bool varySpeed) {
    auto walk = std::make_shared<Locomotion>(nav, settings);
    static const auto humanoid = makeSeedHumanoid();
    for (int i = 0; i < count; ++i) {
        Locomotion::Actor a;
        a.tmpl = humanoid;
        a.walkClip = humanoid->findClip("walk");
        a.start = nav->randomPoint(CounterRng(seed, std::uint64_t(i)), 0);
        if (varySpeed) a.speed = 1.0 + 0.6 * CounterRng(6, std::uint64_t(i)).uniform(0);
        a.stream = std::uint64_t(i);
        walk->addActor(a);
    }
    return walk;
}

}  // namespace throng::sim::test
