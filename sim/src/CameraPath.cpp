#include "throng/sim/CameraPath.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace throng::sim {

CameraPath::CameraPath(CameraDescription description, double extent) : d_(std::move(description)) {
    if (d_.path.empty()) {
        // Circle the town once a minute, from above a corner, looking at its centre.
        for (int k = 0; k <= 8; ++k) {
            const double a = 2.0 * std::numbers::pi * k / 8.0;
            d_.path.push_back(CameraKey{7.5 * k, glm::dvec3(0.6 * extent * std::cos(a), 0.18 * extent + 12.0, 0.6 * extent * std::sin(a)),
                                        glm::dvec3(0.0, 1.5, 0.0)});
        }
    }
}

double CameraPath::duration() const { return d_.path.back().time - d_.path.front().time; }

Camera CameraPath::at(double time, double aspect) const {
    if (!(aspect > 0.0) || !std::isfinite(aspect)) throw std::invalid_argument("CameraPath::at: argument 'aspect' must be positive");
    const auto& p = d_.path;
    CameraKey k = p.back();
    if (time <= p.front().time) {
        k = p.front();
    } else {
        for (std::size_t i = 1; i < p.size(); ++i)
            if (time < p[i].time) {
                const double u = (time - p[i - 1].time) / (p[i].time - p[i - 1].time);
                k.eye = glm::mix(p[i - 1].eye, p[i].eye, u);
                k.target = glm::mix(p[i - 1].target, p[i].target, u);
                break;
            }
    }
    Camera c;
    c.setPerspective(d_.fovDegrees * std::numbers::pi / 180.0, aspect, d_.nearDistance, d_.farDistance);
    const glm::dvec3 dir = glm::normalize(k.target - k.eye);
    c.setLookAt(k.eye, k.target, std::abs(dir.y) > 0.999 ? glm::dvec3(0, 0, 1) : glm::dvec3(0, 1, 0));
    return c;
}

}  // namespace throng::sim
