#include "throng/testkit/RandomScenes.h"

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "throng/scenegraph/Geometry.h"
#include "throng/scenegraph/LOD.h"
#include "throng/scenegraph/Transform.h"

namespace throng::testkit {
namespace {

// Builds "<prefix><n>" (written out because GCC 12 warns falsely on "literal" + std::to_string at -O3).
std::string numbered(const char* prefix, int n) {
    std::string s(prefix);
    s += std::to_string(n);
    return s;
}

double uniform(std::mt19937_64& rng, double lo, double hi) {
    return std::uniform_real_distribution<double>(lo, hi)(rng);
}

Vec3 uniformVec(std::mt19937_64& rng, double lo, double hi) {
    return Vec3(uniform(rng, lo, hi), uniform(rng, lo, hi), uniform(rng, lo, hi));
}

Quat randomRotation(std::mt19937_64& rng) {
    Quat q(uniform(rng, -1, 1), uniform(rng, -1, 1), uniform(rng, -1, 1), uniform(rng, -1, 1));
    return glm::length(q) < 1e-3 ? Quat(1, 0, 0, 0) : glm::normalize(q);
}

class Builder {
public:
    Builder(std::mt19937_64& rng, const RandomSceneParams& p) : rng_(rng), p_(p) {
        for (int i = 0; i < 16; ++i) {
            const double r = std::exp(uniform(rng_, std::log(0.05), std::log(20.0)));
            drawables_.push_back(std::make_shared<Drawable>(
                numbered("drawable", i), BoundingSphere(uniformVec(rng_, -1, 1), r),
                static_cast<std::uint64_t>(1 + i * 37)));
        }
    }

    std::shared_ptr<Node> randomTransform(int depth, const Vec3& translation) {
        auto t = std::make_shared<Transform>();
        t->setName(numbered("t", counter_++));
        if (std::bernoulli_distribution(0.15)(rng_)) {
            // A matrix with shear, which the bound transform must still enclose.
            Mat4 m = glm::mat4_cast(randomRotation(rng_));
            m[1] += Vec4(uniform(rng_, -0.5, 0.5), 0, uniform(rng_, -0.5, 0.5), 0);
            m[3] = Vec4(translation, 1.0);
            t->setMatrix(m);
        } else {
            TransformDofs d;
            d.translation = translation;
            d.rotation = randomRotation(rng_);
            d.scale = std::bernoulli_distribution(0.3)(rng_) ? uniformVec(rng_, 0.3, 3.0) : Vec3(1.0);
            t->setDofs(d);
        }
        const int children = std::uniform_int_distribution<int>(1, 4)(rng_);
        for (int i = 0; i < children; ++i) t->addChild(randomChild(depth + 1));
        return t;
    }

    std::shared_ptr<Node> randomChild(int depth) {
        const int kind = depth >= p_.maxDepth ? 0 : std::uniform_int_distribution<int>(0, 3)(rng_);
        if (kind == 0) return leaf();
        if (kind == 1) return randomTransform(depth, uniformVec(rng_, -5, 5));
        if (kind == 2) {
            auto lod = std::make_shared<LOD>();
            lod->setName(numbered("lod", counter_++));
            lod->setCenter(uniformVec(rng_, -2, 2));
            double range = uniform(rng_, 5, 60);
            const int levels = std::uniform_int_distribution<int>(1, 3)(rng_);
            for (int i = 0; i < levels; ++i) {
                lod->addChild(randomChild(depth + 1), range);
                range *= uniform(rng_, 1.5, 4.0);
            }
            return lod;
        }
        auto g = std::make_shared<Group>();
        g->setName(numbered("g", counter_++));
        const int children = std::uniform_int_distribution<int>(1, 3)(rng_);
        for (int i = 0; i < children; ++i) g->addChild(randomChild(depth + 1));
        return g;
    }

    std::shared_ptr<Node> leaf() {
        const auto& d = drawables_[std::uniform_int_distribution<std::size_t>(0, drawables_.size() - 1)(rng_)];
        return std::make_shared<Geometry>(d);
    }

private:
    std::mt19937_64& rng_;
    RandomSceneParams p_;
    std::vector<std::shared_ptr<const Drawable>> drawables_;
    int counter_ = 0;
};

}  // namespace

std::shared_ptr<Group> buildRandomScene(std::mt19937_64& rng, const RandomSceneParams& params) {
    Builder b(rng, params);
    auto root = std::make_shared<Group>();
    root->setName("root");
    for (int i = 0; i < params.objects; ++i)
        root->addChild(b.randomTransform(0, params.origin + uniformVec(rng, -params.extent, params.extent)));
    return root;
}

Camera randomCamera(std::mt19937_64& rng, double extent, const Vec3& origin) {
    Camera c;
    const double fov = uniform(rng, 5.0, 120.0) * std::numbers::pi / 180.0;
    const double nearDistance = std::exp(uniform(rng, std::log(0.01), std::log(1.0)));
    c.setPerspective(fov, uniform(rng, 0.5, 2.5), nearDistance, nearDistance * std::exp(uniform(rng, std::log(50.0), std::log(1e5))));
    Vec3 eye = origin + uniformVec(rng, -1.2 * extent, 1.2 * extent);
    Vec3 target = origin + uniformVec(rng, -extent, extent);
    if (glm::length(target - eye) < 1e-3) target = eye + Vec3(1, 0, 0);
    Vec3 up = glm::normalize(uniformVec(rng, -1, 1) + Vec3(0, 2, 0));
    if (glm::length(glm::cross(glm::normalize(target - eye), up)) < 1e-3) up = Vec3(1, 0, 0);
    c.setLookAt(eye, target, up);
    return c;
}

}  // namespace throng::testkit
