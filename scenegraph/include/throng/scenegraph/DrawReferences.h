#pragma once
// Numbers for the things draw items point to (drawables, the nodes that made them, key-pose
// sources), so that items can travel between processes as records (DrawRecords.h): two processes
// that build the same scene and number its things in the same order read each other's records
// as their own items. Numbers are given in order of adding, from 0, per kind.

#include <cstdint>
#include <unordered_map>
#include <vector>

namespace throng {

class Drawable;
class KeyPoseSource;
class Node;

/// The numbering of one process's drawables, nodes and key-pose sources.
class DrawReferences {
public:
    /// Marks "no such thing" (an item without a key-pose source).
    static constexpr std::uint32_t kNone = ~std::uint32_t{0};

    /// Numbers `drawable` unless it has a number; returns its number.
    std::uint32_t addDrawable(const Drawable& drawable) { return add(drawables_, drawableNumber_, &drawable); }
    /// Numbers `node` unless it has a number; returns its number. Records are merged in order of
    /// node number: number nodes in the order a traversal meets them.
    std::uint32_t addNode(const Node& node) { return add(nodes_, nodeNumber_, &node); }
    /// Numbers `source` unless it has a number; returns its number.
    std::uint32_t addKeyPoseSource(const KeyPoseSource& source) { return add(sources_, sourceNumber_, &source); }

    /// The number of `drawable`, or kNone.
    std::uint32_t numberOf(const Drawable* drawable) const { return find(drawableNumber_, drawable); }
    /// The number of `node`, or kNone.
    std::uint32_t numberOf(const Node* node) const { return find(nodeNumber_, node); }
    /// The number of `source`, or kNone.
    std::uint32_t numberOf(const KeyPoseSource* source) const { return find(sourceNumber_, source); }

    /// Drawable number `n`, or null when there is none.
    const Drawable* drawable(std::uint32_t n) const { return n < drawables_.size() ? drawables_[n] : nullptr; }
    /// Node number `n`, or null.
    const Node* node(std::uint32_t n) const { return n < nodes_.size() ? nodes_[n] : nullptr; }
    /// Key-pose source number `n`, or null.
    const KeyPoseSource* keyPoseSource(std::uint32_t n) const { return n < sources_.size() ? sources_[n] : nullptr; }

    /// Numbered drawables.
    std::size_t drawableCount() const { return drawables_.size(); }
    /// Numbered nodes.
    std::size_t nodeCount() const { return nodes_.size(); }
    /// Numbered key-pose sources.
    std::size_t keyPoseSourceCount() const { return sources_.size(); }

private:
    template <class T>
    static std::uint32_t add(std::vector<const T*>& list, std::unordered_map<const void*, std::uint32_t>& number, const T* p) {
        const auto [at, added] = number.try_emplace(p, static_cast<std::uint32_t>(list.size()));
        if (added) list.push_back(p);
        return at->second;
    }
    static std::uint32_t find(const std::unordered_map<const void*, std::uint32_t>& number, const void* p) {
        const auto at = number.find(p);
        return at == number.end() ? kNone : at->second;
    }
    std::vector<const Drawable*> drawables_;
    std::vector<const Node*> nodes_;
    std::vector<const KeyPoseSource*> sources_;
    std::unordered_map<const void*, std::uint32_t> drawableNumber_, nodeNumber_, sourceNumber_;
};

}  // namespace throng
