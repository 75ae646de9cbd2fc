#include "throng/render/ImpostorAtlas.h"

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <numeric>
#include <sstream>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "throng/render/ImageIO.h"
#include "throng/scenegraph/BodyLook.h"
#include "throng/scenegraph/WholeFile.h"

namespace throng {
namespace {

std::string pageFile(int keyframe) { return "keyframe-" + std::to_string(keyframe) + ".png"; }

Image blankPage(const ViewHemisphere& views, int rows, int cellSize, const std::string& name) {
    Image page;
    page.name = name;
    page.width = views.azimuths() * cellSize;
    page.height = rows * cellSize;
    page.rgba.assign(static_cast<std::size_t>(page.width) * page.height * 4, 0);
    return page;
}

}  // namespace

ImpostorAtlas::ImpostorAtlas(std::string templateName, std::string clipName, const ViewHemisphere& views, int keyframes,
                             double duration, int cellSize, std::vector<std::string> boneNames)
    : templateName_(std::move(templateName)), clipName_(std::move(clipName)), views_(views), keyframes_(keyframes),
      duration_(duration), cellSize_(cellSize), boneNames_(std::move(boneNames)) {
    if (keyframes < 2) throw std::invalid_argument("ImpostorAtlas: at least 2 key-frames, got " + std::to_string(keyframes));
    if (cellSize < 8 || cellSize > 4096) throw std::invalid_argument("ImpostorAtlas: cell size out of range");
    if (!(duration > 0.0) || !std::isfinite(duration)) throw std::invalid_argument("ImpostorAtlas: duration must be positive");
    importance_.assign(boneNames_.size(), 1.0f);
    ringRow_.resize(static_cast<std::size_t>(views_.elevations()));
    std::iota(ringRow_.begin(), ringRow_.end(), 0);
    for (int k = 0; k < keyframes; ++k)
        pages_.push_back(blankPage(views_, views_.elevations(), cellSize_, templateName_ + "/" + pageFile(k)));
    lines_.resize(static_cast<std::size_t>(keyframes) * views_.viewCount() * boneNames_.size());
}

void ImpostorAtlas::setBoneImportance(std::vector<float> importance) {
    if (importance.size() != boneNames_.size()) throw std::invalid_argument("ImpostorAtlas: one importance per bone");
    importance_ = std::move(importance);
}

std::vector<std::uint32_t> ImpostorAtlas::strongestBones(std::size_t count) const {
    std::vector<std::uint32_t> order(boneNames_.size());
    std::iota(order.begin(), order.end(), 0u);
    std::stable_sort(order.begin(), order.end(), [&](auto a, auto b) { return importance_[a] > importance_[b]; });
    order.resize(std::min(count, order.size()));
    std::sort(order.begin(), order.end());
    return order;
}

std::pair<int, int> ImpostorAtlas::cellOrigin(const char* who, std::uint32_t view, int keyframe) const {
    if (view >= views_.viewCount() || keyframe < 0 || keyframe >= keyframes_)
        throw std::invalid_argument(std::string("ImpostorAtlas::") + who + ": view " + std::to_string(view) + " key-frame " +
                                    std::to_string(keyframe) + " out of range");
    if (!stored(keyframe)) throw std::invalid_argument(std::string("ImpostorAtlas::") + who + ": key-frame " + std::to_string(keyframe) + " is dropped");
    const auto azimuths = static_cast<std::uint32_t>(views_.azimuths());
    const int row = ringRow_[view / azimuths];
    if (row < 0)
        throw std::invalid_argument(std::string("ImpostorAtlas::") + who + ": view " + std::to_string(view) + " is on dropped ring " +
                                    std::to_string(view / azimuths));
    return {static_cast<int>(view % azimuths) * cellSize_, row * cellSize_};
}

void ImpostorAtlas::setCell(std::uint32_t view, int keyframe, const Image& cell) {
    const auto [x0, y0] = cellOrigin("setCell", view, keyframe);
    if (cell.width != cellSize_ || cell.height != cellSize_ || !cell.valid())
        throw std::invalid_argument("ImpostorAtlas::setCell: the cell is not " + std::to_string(cellSize_) + " pixels square");
    Image& page = pages_[static_cast<std::size_t>(keyframe)];
    const std::size_t row = static_cast<std::size_t>(cellSize_) * 4;
    for (int y = 0; y < cellSize_; ++y)
        std::copy_n(cell.rgba.data() + y * row, row,
                    page.rgba.data() + (static_cast<std::size_t>(y0 + y) * page.width + x0) * 4);
}

Image ImpostorAtlas::cell(std::uint32_t view, int keyframe) const {
    const auto [x0, y0] = cellOrigin("cell", view, keyframe);
    const Image& page = pages_[static_cast<std::size_t>(keyframe)];
    Image out;
    out.name = templateName_ + " view " + std::to_string(view) + " key-frame " + std::to_string(keyframe);
    out.width = out.height = cellSize_;
    out.rgba.resize(static_cast<std::size_t>(cellSize_) * cellSize_ * 4);
    const std::size_t row = static_cast<std::size_t>(cellSize_) * 4;
    for (int y = 0; y < cellSize_; ++y)
        std::copy_n(page.rgba.data() + (static_cast<std::size_t>(y0 + y) * page.width + x0) * 4, row,
                    out.rgba.data() + y * row);
    return out;
}

std::span<const FeatureLine> ImpostorAtlas::lines(std::uint32_t view, int keyframe) const {
    const std::size_t n = boneNames_.size();
    return {lines_.data() + (static_cast<std::size_t>(keyframe) * views_.viewCount() + view) * n, n};
}

std::span<FeatureLine> ImpostorAtlas::lines(std::uint32_t view, int keyframe) {
    const std::size_t n = boneNames_.size();
    return {lines_.data() + (static_cast<std::size_t>(keyframe) * views_.viewCount() + view) * n, n};
}

void ImpostorAtlas::dropOddKeyframes() {
    for (int k = 1; k < keyframes_; k += 2)
        if (!(keyframes_ % 2 == 1 && k == keyframes_ - 1)) pages_[static_cast<std::size_t>(k)] = Image{};
}

void ImpostorAtlas::dropOddRings() {
    const int rings = views_.elevations();
    if (rings < 2) throw std::invalid_argument("ImpostorAtlas::dropOddRings: '" + templateName_ + "' has a single view ring");
    std::vector<int> rows(static_cast<std::size_t>(rings), -1);
    int kept = 0;
    for (int e = 0; e < rings; ++e)
        if (e % 2 == 0 && ringStored(e)) rows[static_cast<std::size_t>(e)] = kept++;
    // Each stored page is rebuilt with the kept rings' rows only: the memory really goes.
    const std::size_t rowBytes = static_cast<std::size_t>(views_.azimuths()) * cellSize_ * cellSize_ * 4;
    for (Image& page : pages_) {
        if (page.rgba.empty()) continue;
        Image compact = blankPage(views_, kept, cellSize_, page.name);
        for (int e = 0; e < rings; ++e)
            if (rows[static_cast<std::size_t>(e)] >= 0)
                std::copy_n(page.rgba.data() + static_cast<std::size_t>(ringRow_[static_cast<std::size_t>(e)]) * rowBytes, rowBytes,
                            compact.rgba.data() + static_cast<std::size_t>(rows[static_cast<std::size_t>(e)]) * rowBytes);
        page = std::move(compact);
    }
    ringRow_ = std::move(rows);
}

void ImpostorAtlas::drop(AtlasStorage storage) {
    if (storage != AtlasStorage::Full) dropOddKeyframes();
    if (storage == AtlasStorage::Half) dropOddRings();
}

void ImpostorAtlas::ringNeighbours(int ring, int& below, int& above, float& t) const {
    if (ring < 0 || ring >= views_.elevations())
        throw std::invalid_argument("ImpostorAtlas::ringNeighbours: ring " + std::to_string(ring) + " out of range");
    if (ringStored(ring)) throw std::invalid_argument("ImpostorAtlas::ringNeighbours: ring " + std::to_string(ring) + " is stored");
    int b = ring - 1, a = ring + 1;
    while (b >= 0 && !ringStored(b)) --b;
    while (a < views_.elevations() && !ringStored(a)) ++a;
    if (b < 0 && a >= views_.elevations()) throw std::invalid_argument("ImpostorAtlas::ringNeighbours: no stored ring");
    if (b < 0) b = a;
    if (a >= views_.elevations()) a = b;
    below = b, above = a;
    t = a == b ? 0.0f : static_cast<float>(ring - b) / static_cast<float>(a - b);
}

CellSources ImpostorAtlas::sources(std::uint32_t view, int keyframe) const {
    if (view >= views_.viewCount() || keyframe < 0 || keyframe >= keyframes_)
        throw std::invalid_argument("ImpostorAtlas::sources: view " + std::to_string(view) + " key-frame " + std::to_string(keyframe) +
                                    " out of range");
    const auto azimuths = static_cast<std::uint32_t>(views_.azimuths());
    const int ring = static_cast<int>(view / azimuths);
    int k0 = keyframe, k1 = keyframe, r0 = ring, r1 = ring;
    float tk = 0.0f, tr = 0.0f;
    if (!stored(keyframe)) neighbours(keyframe, k0, k1, tk);
    if (!ringStored(ring)) ringNeighbours(ring, r0, r1, tr);
    CellSources out;
    const auto add = [&](int r, int k, float w) {
        const std::uint32_t v = static_cast<std::uint32_t>(r) * azimuths + view % azimuths;
        for (int i = 0; i < out.count; ++i)
            if (out.cells[static_cast<std::size_t>(i)].view == v && out.cells[static_cast<std::size_t>(i)].keyframe == k) {
                out.cells[static_cast<std::size_t>(i)].weight += w;
                return;
            }
        if (w > 0.0f) out.cells[static_cast<std::size_t>(out.count++)] = {v, k, w};
    };
    add(r0, k0, (1.0f - tr) * (1.0f - tk));
    add(r0, k1, (1.0f - tr) * tk);
    add(r1, k0, tr * (1.0f - tk));
    add(r1, k1, tr * tk);
    return out;
}

void ImpostorAtlas::neighbours(int keyframe, int& before, int& after, float& t) const {
    if (stored(keyframe)) throw std::invalid_argument("ImpostorAtlas::neighbours: key-frame " + std::to_string(keyframe) + " is stored");
    int b = keyframe, a = keyframe, db = 0, da = 0;
    do b = (b + keyframes_ - 1) % keyframes_, ++db; while (!stored(b) && db < keyframes_);
    do a = (a + 1) % keyframes_, ++da; while (!stored(a) && da < keyframes_);
    if (!stored(b) || !stored(a)) throw std::invalid_argument("ImpostorAtlas::neighbours: no stored key-frame");
    before = b, after = a;
    t = static_cast<float>(db) / static_cast<float>(db + da);
}

std::size_t ImpostorAtlas::textureBytes() const {
    std::size_t bytes = 0;
    for (const Image& p : pages_) bytes += p.rgba.size();
    return bytes;
}

void ImpostorAtlas::checkProxy(const ProxyMesh* proxy, const char* who) const {
    if (proxy && (proxy->keyframeCount() != keyframes_ || proxy->cellSize() != cellSize_))
        throw std::invalid_argument(std::string("ImpostorAtlas::") + who + ": the proxy has " + std::to_string(proxy->keyframeCount()) +
                                    " key-frames of " + std::to_string(proxy->cellSize()) + " px cells, the atlas " +
                                    std::to_string(keyframes_) + " of " + std::to_string(cellSize_) + " px");
}

void ImpostorAtlas::setProxy(std::shared_ptr<const ProxyMesh> proxy) {
    checkProxy(proxy.get(), "setProxy");
    proxy_ = std::move(proxy);
}

void ImpostorAtlas::setDrawProxy(std::shared_ptr<const ProxyMesh> proxy) {
    checkProxy(proxy.get(), "setDrawProxy");
    drawProxy_ = std::move(proxy);
}

std::size_t ImpostorAtlas::fullTextureBytes() const {
    return static_cast<std::size_t>(keyframes_) * views_.viewCount() * cellSize_ * cellSize_ * 4;
}

std::span<const std::uint8_t> ImpostorAtlas::regions(std::uint32_t view, int keyframe) const {
    if (regions_.empty()) return {};
    if (view >= views_.viewCount() || keyframe < 0 || keyframe >= keyframes_)
        throw std::invalid_argument("ImpostorAtlas::regions: cell (" + std::to_string(view) + ", " + std::to_string(keyframe) + ") out of range");
    const std::size_t texels = static_cast<std::size_t>(cellSize_) * static_cast<std::size_t>(cellSize_);
    return {regions_.data() + (static_cast<std::size_t>(keyframe) * views_.viewCount() + view) * texels, texels};
}

void ImpostorAtlas::setRegions(std::uint32_t view, int keyframe, std::span<const std::uint8_t> regions) {
    const std::size_t texels = static_cast<std::size_t>(cellSize_) * static_cast<std::size_t>(cellSize_);
    if (view >= views_.viewCount() || keyframe < 0 || keyframe >= keyframes_)
        throw std::invalid_argument("ImpostorAtlas::setRegions: cell (" + std::to_string(view) + ", " + std::to_string(keyframe) + ") out of range");
    if (regions.size() != texels)
        throw std::invalid_argument("ImpostorAtlas::setRegions: " + std::to_string(regions.size()) + " regions for a cell of " +
                                    std::to_string(texels) + " texels");
    for (std::uint8_t r : regions)
        if (r > kBodyRegionCount) throw std::invalid_argument("ImpostorAtlas::setRegions: region " + std::to_string(r) + " is not 0-4");
    if (regions_.empty()) regions_.assign(texels * views_.viewCount() * static_cast<std::size_t>(keyframes_), 0);
    std::copy(regions.begin(), regions.end(), regions_.begin() + static_cast<std::ptrdiff_t>((static_cast<std::size_t>(keyframe) * views_.viewCount() + view) * texels));
}

namespace {

// Top-left pixel of view `v`'s cell in a region page (ring r in row r, as colour pages are).
std::pair<int, int> regionCellOrigin(const ViewHemisphere& views, std::uint32_t v, int size) {
    const auto azimuths = static_cast<std::uint32_t>(views.azimuths());
    return {static_cast<int>(v % azimuths) * size, static_cast<int>(v / azimuths) * size};
}

// A key-frame's regions laid out as a full page of every view (ring r in row r, as pages are),
// the region times 60 in red.
Image regionPage(const ImpostorAtlas& atlas, int keyframe) {
    const ViewHemisphere& views = atlas.views();
    const int size = atlas.cellSize();
    Image page;
    page.name = "regions " + std::to_string(keyframe);
    page.width = views.azimuths() * size;
    page.height = views.elevations() * size;
    page.rgba.assign(static_cast<std::size_t>(page.width) * static_cast<std::size_t>(page.height) * 4, 0);
    for (std::uint32_t v = 0; v < views.viewCount(); ++v) {
        const std::span<const std::uint8_t> cell = atlas.regions(v, keyframe);
        const auto [x0, y0] = regionCellOrigin(views, v, size);
        for (int y = 0; y < size; ++y)
            for (int x = 0; x < size; ++x) {
                std::uint8_t* px = &page.rgba[(static_cast<std::size_t>(y0 + y) * static_cast<std::size_t>(page.width) + static_cast<std::size_t>(x0 + x)) * 4];
                px[0] = static_cast<std::uint8_t>(cell[static_cast<std::size_t>(y) * static_cast<std::size_t>(size) + static_cast<std::size_t>(x)] * 60);
                px[3] = 255;
            }
    }
    return page;
}

std::string regionFile(int keyframe) {
    char name[32];
    std::snprintf(name, sizeof name, "regions-%03d.png", keyframe);
    return name;
}

}  // namespace

void ImpostorAtlas::save(const std::filesystem::path& directory) const {
    std::filesystem::create_directories(directory);
    nlohmann::json j;
    j["template"] = templateName_;
    j["clip"] = clipName_;
    j["duration"] = duration_;
    j["cellSize"] = cellSize_;
    j["views"] = {{"azimuths", views_.azimuths()}, {"elevations", views_.elevations()},
                  {"topElevation", views_.elevation(views_.elevations() - 1)}};
    nlohmann::json viewList = nlohmann::json::array();
    for (std::uint32_t v = 0; v < views_.viewCount(); ++v) {
        const glm::vec3 d = views_.direction(v);
        viewList.push_back({{"index", v}, {"azimuth", views_.azimuth(static_cast<int>(v) % views_.azimuths())},
                            {"elevation", views_.elevation(static_cast<int>(v) / views_.azimuths())},
                            {"direction", {d.x, d.y, d.z}}});
    }
    j["views"]["list"] = viewList;
    nlohmann::json rings = nlohmann::json::array();
    for (int e = 0; e < views_.elevations(); ++e) rings.push_back(ringStored(e));
    j["views"]["ringsStored"] = rings;
    j["bounds"] = {{"centre", {centre_.x, centre_.y, centre_.z}}, {"radius", radius_}};
    j["bones"] = boneNames_;
    j["boneImportance"] = importance_;
    nlohmann::json frames = nlohmann::json::array();
    for (int k = 0; k < keyframes_; ++k) {
        nlohmann::json f;
        f["index"] = k;
        f["time"] = duration_ * k / keyframes_;
        f["stored"] = stored(k);
        if (stored(k)) f["page"] = pageFile(k);
        nlohmann::json segs = nlohmann::json::array();
        for (std::uint32_t v = 0; v < views_.viewCount(); ++v) {
            nlohmann::json cellLines = nlohmann::json::array();
            for (const FeatureLine& l : lines(v, k)) cellLines.push_back({l.p.x, l.p.y, l.q.x, l.q.y});
            segs.push_back(cellLines);
        }
        f["segments"] = segs;
        frames.push_back(f);
    }
    j["keyframes"] = frames;
    j["textureBytes"] = textureBytes();
    j["fullTextureBytes"] = fullTextureBytes();
    if (hasRegions()) j["regions"] = nlohmann::json{{"bytes", regionBytes()}, {"scale", 60}};
    for (int k = 0; k < keyframes_; ++k) {
        if (stored(k)) writePng(pages_[static_cast<std::size_t>(k)], directory / pageFile(k));
        if (hasRegions()) writePng(regionPage(*this, k), directory / regionFile(k));
    }
    // Last and whole: a folder with an impostor.json holds every page it lists.
    try {
        writeWholeFile(directory / "impostor.json", j.dump(1) + '\n');
    } catch (const std::runtime_error& e) {
        throw std::runtime_error(std::string("ImpostorAtlas::save: ") + e.what());
    }
}

ImpostorAtlas ImpostorAtlas::load(const std::filesystem::path& directory) {
    const std::filesystem::path file = directory / "impostor.json";
    std::ifstream in(file);
    if (!in) throw std::runtime_error("ImpostorAtlas::load: cannot open " + file.string());
    try {
        const nlohmann::json j = nlohmann::json::parse(in);
        const auto& jv = j.at("views");
        ViewHemisphere views(jv.at("azimuths").get<int>(), jv.at("elevations").get<int>(), jv.at("topElevation").get<float>());
        const auto& frames = j.at("keyframes");
        ImpostorAtlas atlas(j.at("template").get<std::string>(), j.at("clip").get<std::string>(), views,
                            static_cast<int>(frames.size()), j.at("duration").get<double>(), j.at("cellSize").get<int>(),
                            j.at("bones").get<std::vector<std::string>>());
        atlas.setBoneImportance(j.at("boneImportance").get<std::vector<float>>());
        if (jv.contains("ringsStored")) {  // absent in atlases saved before rings could be dropped: all stored
            const auto flags = jv.at("ringsStored").get<std::vector<bool>>();
            if (flags.size() != static_cast<std::size_t>(views.elevations()))
                throw std::runtime_error("views.ringsStored has " + std::to_string(flags.size()) + " entries for " +
                                         std::to_string(views.elevations()) + " rings");
            int kept = 0;
            for (std::size_t e = 0; e < flags.size(); ++e) atlas.ringRow_[e] = flags[e] ? kept++ : -1;
            if (kept == 0) throw std::runtime_error("views.ringsStored keeps no ring");
            for (int k = 0; k < atlas.keyframes_; ++k)
                atlas.pages_[static_cast<std::size_t>(k)] = blankPage(views, kept, atlas.cellSize_, atlas.pages_[static_cast<std::size_t>(k)].name);
        }
        const auto& c = j.at("bounds").at("centre");
        atlas.setWorldBounds({c.at(0).get<float>(), c.at(1).get<float>(), c.at(2).get<float>()},
                             j.at("bounds").at("radius").get<float>());
        for (int k = 0; k < atlas.keyframes_; ++k) {
            const auto& f = frames.at(static_cast<std::size_t>(k));
            if (f.at("stored").get<bool>()) {
                Image page = readPng(directory / f.at("page").get<std::string>());
                if (page.width != atlas.pages_[static_cast<std::size_t>(k)].width ||
                    page.height != atlas.pages_[static_cast<std::size_t>(k)].height)
                    throw std::runtime_error("page " + std::to_string(k) + " has the wrong size");
                atlas.pages_[static_cast<std::size_t>(k)] = std::move(page);
            } else {
                atlas.pages_[static_cast<std::size_t>(k)] = Image{};
            }
            if (j.contains("regions")) {
                const Image page = readPng(directory / regionFile(k));
                const int size = atlas.cellSize_;
                if (page.width != views.azimuths() * size || page.height != views.elevations() * size)
                    throw std::runtime_error(regionFile(k) + " has the wrong size");
                std::vector<std::uint8_t> cell(static_cast<std::size_t>(size) * static_cast<std::size_t>(size));
                for (std::uint32_t v = 0; v < views.viewCount(); ++v) {
                    const auto [x0, y0] = regionCellOrigin(views, v, size);
                    for (int y = 0; y < size; ++y)
                        for (int x = 0; x < size; ++x) {
                            const int red = page.rgba[(static_cast<std::size_t>(y0 + y) * static_cast<std::size_t>(page.width) + static_cast<std::size_t>(x0 + x)) * 4];
                            if (red % 60 != 0 || red / 60 > static_cast<int>(kBodyRegionCount))
                                throw std::runtime_error(regionFile(k) + ": pixel (" + std::to_string(x0 + x) + ", " + std::to_string(y0 + y) +
                                                         ") is not a region (red " + std::to_string(red) + ")");
                            cell[static_cast<std::size_t>(y) * static_cast<std::size_t>(size) + static_cast<std::size_t>(x)] = static_cast<std::uint8_t>(red / 60);
                        }
                    atlas.setRegions(v, k, cell);
                }
            }
            const auto& segs = f.at("segments");
            for (std::uint32_t v = 0; v < views.viewCount(); ++v) {
                std::span<FeatureLine> out = atlas.lines(v, k);
                const auto& cellLines = segs.at(v);
                if (cellLines.size() != out.size()) throw std::runtime_error("wrong number of segments");
                for (std::size_t b = 0; b < out.size(); ++b)
                    out[b] = {{cellLines[b].at(0).get<float>(), cellLines[b].at(1).get<float>()},
                              {cellLines[b].at(2).get<float>(), cellLines[b].at(3).get<float>()}};
            }
        }
        return atlas;
    } catch (const std::runtime_error& e) {
        throw std::runtime_error("ImpostorAtlas::load: " + file.string() + ": " + e.what());
    } catch (const std::exception& e) {
        throw std::runtime_error("ImpostorAtlas::load: " + file.string() + ": " + e.what());
    }
}

void ImpostorAtlas::applyFeatureFile(const std::filesystem::path& file) {
    std::ifstream in(file);
    if (!in) throw std::runtime_error("ImpostorAtlas::applyFeatureFile: cannot open " + file.string());
    try {
        const nlohmann::json j = nlohmann::json::parse(in);
        if (j.contains("bones")) {
            std::vector<std::uint32_t> keep;
            for (const auto& name : j.at("bones")) {
                const auto it = std::find(boneNames_.begin(), boneNames_.end(), name.get<std::string>());
                if (it == boneNames_.end()) throw std::runtime_error("no bone named '" + name.get<std::string>() + "'");
                keep.push_back(static_cast<std::uint32_t>(it - boneNames_.begin()));
            }
            std::vector<FeatureLine> lines;
            std::vector<std::string> names;
            std::vector<float> importance;
            for (std::uint32_t b : keep) names.push_back(boneNames_[b]), importance.push_back(importance_[b]);
            for (int k = 0; k < keyframes_; ++k)
                for (std::uint32_t v = 0; v < views_.viewCount(); ++v)
                    for (std::uint32_t b : keep) lines.push_back(this->lines(v, k)[b]);
            boneNames_ = std::move(names), importance_ = std::move(importance), lines_ = std::move(lines);
        }
        if (j.contains("cells"))
            for (const auto& c : j.at("cells")) {
                const auto view = c.at("view").get<std::uint32_t>();
                const int k = c.at("keyframe").get<int>();
                if (view >= views_.viewCount() || k < 0 || k >= keyframes_) throw std::runtime_error("cell out of range");
                std::span<FeatureLine> out = lines(view, k);
                const auto& ls = c.at("lines");
                if (ls.size() != out.size()) throw std::runtime_error("a cell needs one line per bone");
                for (std::size_t b = 0; b < out.size(); ++b)
                    out[b] = {{ls[b].at(0).get<float>(), ls[b].at(1).get<float>()}, {ls[b].at(2).get<float>(), ls[b].at(3).get<float>()}};
            }
    } catch (const std::exception& e) {
        throw std::runtime_error("ImpostorAtlas::applyFeatureFile: " + file.string() + ": " + e.what());
    }
}

}  // namespace throng
