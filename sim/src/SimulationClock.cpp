#include "throng/sim/SimulationClock.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace throng::sim {

SimulationClock::SimulationClock(double step) : step_(step) {
    if (!std::isfinite(step) || !(step > 0.0))
        throw std::invalid_argument("SimulationClock: argument 'step' must be positive and finite, got " + std::to_string(step));
}

}  // namespace throng::sim
