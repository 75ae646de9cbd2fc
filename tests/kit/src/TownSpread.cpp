#include "throng/testkit/TownSpread.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <random>

#include "throng/actors/ActorGroup.h"
#include "throng/actors/KeyframeBehaviour.h"
#include "throng/actors/SeedHumanoid.h"

namespace throng::testkit {

std::vector<KeyframeBehaviour::Actor> circleWalkers(std::shared_ptr<const ActorTemplate> tmpl, int clip, std::size_t count, double extent,
                                                    std::mt19937_64& rng) {
    std::uniform_real_distribution<double> u(0.0, 1.0);
    std::vector<KeyframeBehaviour::Actor> walkers(count);
    for (KeyframeBehaviour::Actor& a : walkers) {
        a.tmpl = tmpl;
        a.clip = clip;
        a.position = Vec3(extent * (u(rng) - 0.5), 0.0, extent * (u(rng) - 0.5));
        a.heading = 6.283 * u(rng);
        a.pathRadius = 3.0 + 10.0 * u(rng);
        a.pathSpeed = 1.2 + 0.4 * u(rng);
        a.timeOffset = 2.0 * u(rng);
    }
    return walkers;
}

TownSpread buildTownSpread(Crowd& crowd, std::size_t actors, double extent, double blockSize, std::uint64_t seed,
                           std::shared_ptr<const ActorTemplate> figure) {
    TownSpread town;
    town.root = std::make_shared<Group>();
    town.root->setName("town");
    const auto humanoid = figure ? std::move(figure) : makeSeedHumanoid();
    const int walkClip = humanoid->findClip("walk");
    auto walk = std::make_shared<KeyframeBehaviour>();
    std::mt19937_64 rng(seed);
    // Actors of one block get consecutive ids, so each group walks its own stretch of the crowd's arrays.
    std::map<std::pair<int, int>, std::vector<KeyframeBehaviour::Actor>> blocks;
    for (const KeyframeBehaviour::Actor& a : circleWalkers(humanoid, std::max(walkClip, 0), actors, extent, rng))
        blocks[{int(std::floor(a.position.x / blockSize)), int(std::floor(a.position.z / blockSize))}].push_back(a);
    for (auto& [key, members] : blocks) {
        std::vector<ActorId> ids;
        for (const KeyframeBehaviour::Actor& a : members) ids.push_back(crowd.add(humanoid, walk, walk->addActor(a)));
        town.root->addChild(crowd.makeGroupNode(std::move(ids)));
    }
    town.camera.setPerspective(1.0, 16.0 / 9.0, 0.1, 1500.0);
    town.camera.setLookAt(Vec3(0, 1.7, 0), Vec3(100, 1.7, 20), Vec3(0, 1, 0));
    return town;
}

}  // namespace throng::testkit
