#include "throng/scenegraph/RecordingBackend.h"

#include "throng/scenegraph/Drawable.h"
#include "throng/scenegraph/DrawList.h"

namespace throng {

void RecordingBackend::beginFrame(const Camera&) {
    records_.clear();
    drawCalls_ = 0;
    primitives_ = 0;
    ++frames_;
}

void RecordingBackend::draw(const DrawList& list) {
    for (const DrawItem& item : list.items()) {
        records_.push_back(Record{item.drawable, item.node, item.instance, item.part, item.lodLevel,
                                  item.world.toMat4()});
        ++drawCalls_;
        primitives_ += item.drawable ? item.drawable->primitiveCount() : 0;
    }
}

void RecordingBackend::endFrame() {}

}  // namespace throng
