#include "PeerScene.h"

#include <cmath>
#include <stdexcept>

#include "throng/research/CostModelScene.h"
#include "throng/actors/KeyframeBehaviour.h"
#include "throng/actors/Table3Template.h"
#include "throng/testkit/TownSpread.h"

namespace throng::peers {

PeerScene buildPeerScene(const std::string& name, std::size_t actors) {
    if (actors == 0) throw std::invalid_argument("buildPeerScene: a scene needs at least one actor");
    PeerScene s;
    s.name = name;
    if (name == "table2") {
        // As bench_actor_processing: Table 2's proportions, every actor in one ActorGroup.
        CostModelScene built = buildTable2Scene(*s.crowd, actors);
        s.root = built.root;
        s.camera = built.camera;
        s.startTime = built.time;
        s.holdTime = true;
    } else if (name == "town" || name == "town-dense") {
        // As bench_actor_processing: density kept constant as the crowd grows (one actor per
        // 1600 m^2, or per 16 m^2 when dense).
        const double spacing = name == "town" ? 40.0 : 4.0;
        testkit::TownSpread town = testkit::buildTownSpread(*s.crowd, actors, spacing * std::sqrt(double(actors)));
        s.root = town.root;
        s.camera = town.camera;
        // The dense crowd is for the check: near and far planes that cut through it decide too.
        if (name == "town-dense") s.camera.setPerspective(1.0, 16.0 / 9.0, 5.0, 60.0);
    } else {
        throw std::invalid_argument("buildPeerScene: unknown scene '" + name + "' (known: table2, town, town-dense)");
    }
    return s;
}

}  // namespace throng::peers
