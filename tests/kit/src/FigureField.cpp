#include "throng/testkit/FigureField.h"

#include <cmath>
#include <string>
#include <vector>

#include "throng/scenegraph/Geometry.h"
#include "throng/scenegraph/LOD.h"
#include "throng/scenegraph/Transform.h"
#include "throng/scenegraph/UpdateCallback.h"

namespace throng::testkit {
namespace {

// Walks a figure round a circle and swings its limbs: the APP work of the demo.
class WalkInCircle : public UpdateCallback {
public:
    WalkInCircle(Vec3 centre, double radius, double phase, std::vector<Transform*> limbs)
        : centre_(centre), radius_(radius), phase_(phase), limbs_(std::move(limbs)) {}
    void update(Node& node, const FrameContext& ctx) override {
        const double a = phase_ + 0.3 * ctx.time;
        TransformDofs dofs;
        dofs.translation = centre_ + Vec3(radius_ * std::cos(a), 0.0, radius_ * std::sin(a));
        dofs.rotation = glm::angleAxis(-a, Vec3(0, 1, 0));
        static_cast<Transform&>(node).setDofs(dofs);
        for (std::size_t i = 0; i < limbs_.size(); ++i) {
            TransformDofs limb = limbs_[i]->dofs();
            const double swing = 0.6 * std::sin(4.0 * ctx.time + phase_ + static_cast<double>(i));
            limb.rotation = glm::angleAxis(swing, Vec3(1, 0, 0));
            limbs_[i]->setDofs(limb);
        }
    }

private:
    Vec3 centre_;
    double radius_, phase_;
    std::vector<Transform*> limbs_;
};

}  // namespace

std::shared_ptr<Group> buildFigureField(int figures) {
    auto part = std::make_shared<Drawable>("limb", BoundingSphere(Vec3(0, -0.35, 0), 0.4), 200);
    auto body = std::make_shared<Drawable>("body", BoundingSphere(Vec3(0, 1.0, 0), 0.9), 1500);
    auto card = std::make_shared<Drawable>("card", BoundingSphere(Vec3(0, 0.9, 0), 1.0), 2);
    const Vec3 limbOffsets[5] = {{0, 1.6, 0}, {-0.25, 1.4, 0}, {0.25, 1.4, 0}, {-0.12, 0.9, 0}, {0.12, 0.9, 0}};

    auto root = std::make_shared<Group>();
    root->setName("field");
    const int side = static_cast<int>(std::ceil(std::sqrt(static_cast<double>(figures))));
    for (int i = 0; i < figures; ++i) {
        auto figure = std::make_shared<Transform>();
        figure->setName("figure" + std::to_string(i));
        auto lod = std::make_shared<LOD>();
        lod->setCenter(Vec3(0, 1, 0));
        auto detailed = std::make_shared<Group>();
        std::vector<Transform*> limbs;
        for (const Vec3& offset : limbOffsets) {
            auto limb = std::make_shared<Transform>();
            TransformDofs d;
            d.translation = offset;
            limb->setDofs(d);
            limb->addChild(std::make_shared<Geometry>(part));
            limbs.push_back(limb.get());
            detailed->addChild(limb);
        }
        detailed->addChild(std::make_shared<Geometry>(body));
        lod->addChild(detailed, 40.0);
        lod->addChild(std::make_shared<Geometry>(body), 150.0);
        lod->addChild(std::make_shared<Geometry>(card), 2000.0);
        figure->addChild(lod);
        const Vec3 centre(8.0 * (i % side), 0.0, 8.0 * (i / side));
        figure->setUpdateCallback(std::make_shared<WalkInCircle>(centre, 2.0, 0.37 * i, limbs));
        root->addChild(figure);
    }
    return root;
}

double figureFieldExtent(int figures) { return 8.0 * std::ceil(std::sqrt(static_cast<double>(figures))); }

}  // namespace throng::testkit
