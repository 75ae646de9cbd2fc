#include "throng/vtk/CrowdRecorder.h"

#include <algorithm>
#include <climits>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <unordered_map>

#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkIdTypeArray.h>
#include <vtkIntArray.h>
#include <vtkLongLongArray.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkStringArray.h>
#include <vtkXMLPolyDataWriter.h>

#include "throng/actors/ActorProcessor.h"
#include "throng/actors/Crowd.h"
#include "throng/scenegraph/DrawList.h"
#include "throng/scenegraph/Node.h"
#include "throng/scenegraph/WholeFile.h"
#include "throng/vtk/CrowdMaps.h"
#include "throng/vtk/ScenePolyData.h"

namespace throng::vtk {
namespace fs = std::filesystem;
namespace {

// Codes of the `tier` and `rejected_at` arrays (the header lists them).
enum Tier : std::int8_t { kNotDrawn = -1, kMesh = 0, kKeyPose = 1, kImpostor = 2 };
const char* const kTierNames[] = {"mesh", "key-pose cache", "impostor"};
const char* const kRejectedAtNames[] = {"none (drawn)", "with its generic group", "CULL 1 (Refpoint Bsphere)",
                                        "CULL 2 (Sklsroot Bsphere)", "occlusion", "CULL 3 (no part visible)",
                                        "not in the scene"};
const char* const kClassNames[] = {"not in scene", "culled with group", "A", "B", "C1", "C2", "C3.1", "C3.2", "occluded"};
static_assert(std::size(kClassNames) == std::size_t(ActorClass::Occluded) + 1, "one name per ActorClass");

int rejectedAt(ActorClass c, std::int8_t tier) {
    switch (c) {
        case ActorClass::NotInScene: return 6;
        case ActorClass::CulledWithGroup: return 1;
        case ActorClass::A: return 2;
        case ActorClass::C1: return 3;
        case ActorClass::Occluded: return 4;
        default: return tier == kNotDrawn ? 5 : 0;  // passed CULL 1 and 2: drawn unless CULL 3 hid every part
    }
}

Tier tierOf(Representation r) {
    switch (r) {
        case Representation::Impostor: return kImpostor;
        case Representation::KeyPose: return kKeyPose;
        default: return kMesh;
    }
}

template <class Array>
vtkSmartPointer<Array> namedArray(const char* name, vtkIdType values) {
    auto a = vtkSmartPointer<Array>::New();
    a->SetName(name);
    a->SetNumberOfValues(values);
    return a;
}

vtkSmartPointer<vtkStringArray> names(const char* name, const auto& list) {
    auto a = vtkSmartPointer<vtkStringArray>::New();
    a->SetName(name);
    for (const auto& s : list) a->InsertNextValue(s);
    return a;
}

// Cells of `count` consecutive ranges of sizes given by size(i), point ids from pointId(i, k).
template <class Size, class PointId>
vtkSmartPointer<vtkCellArray> cells(vtkIdType count, Size size, PointId pointId) {
    auto offsets = vtkSmartPointer<vtkIdTypeArray>::New();
    offsets->SetNumberOfValues(count + 1);
    vtkIdType total = 0;
    offsets->SetValue(0, 0);
    for (vtkIdType i = 0; i < count; ++i) offsets->SetValue(i + 1, total += size(i));
    auto connectivity = vtkSmartPointer<vtkIdTypeArray>::New();
    connectivity->SetNumberOfValues(total);
    vtkIdType at = 0;
    for (vtkIdType i = 0; i < count; ++i)
        for (vtkIdType k = 0; k < size(i); ++k) connectivity->SetValue(at++, pointId(i, k));
    auto array = vtkSmartPointer<vtkCellArray>::New();
    array->SetData(offsets, connectivity);
    return array;
}

vtkSmartPointer<vtkPoints> doublePoints(const double* xyz, std::size_t count) {
    auto points = vtkSmartPointer<vtkPoints>::New();
    points->SetDataTypeToDouble();
    points->SetNumberOfPoints(static_cast<vtkIdType>(count));
    for (std::size_t i = 0; i < count; ++i) points->SetPoint(static_cast<vtkIdType>(i), xyz + 3 * i);
    return points;
}

}  // namespace

CrowdRecorder::CrowdRecorder(fs::path directory, int every) : directory_(std::move(directory)), every_(every) {
    if (every < 1) throw std::invalid_argument("the recording interval must be at least 1 step, not " + std::to_string(every));
    if (directory_.empty()) throw std::invalid_argument("no folder given to record into");
    std::string where = "'";  // appended rather than concatenated: GCC 12 warns falsely (-Wrestrict) at -O3
    where += directory_.string();
    where += '\'';
    std::error_code error;
    if (fs::exists(directory_, error) && !fs::is_directory(directory_, error))
        throw std::invalid_argument(where + " is not a folder");
    fs::create_directories(directory_, error);
    if (error) throw std::invalid_argument("cannot create the folder " + where + ": " + error.message());
    // Permissions alone do not say whether we may write (root, read-only mounts): try.
    const fs::path probe = directory_ / ".throng-write-test";
    {
        std::ofstream out(probe);
        if (!(out << "probe") || !(out.flush())) throw std::invalid_argument("cannot write into the folder " + where);
    }
    fs::remove(probe, error);
}

CrowdRecorder::~CrowdRecorder() {
    if (finished_) return;
    try {
        finish();
    } catch (const std::exception& e) {
        std::fprintf(stderr, "CrowdRecorder: %s\n", e.what());
    }
}

void CrowdRecorder::write(vtkPolyData& data, const std::string& name) const {
    const fs::path path = directory_ / name;
    auto writer = vtkSmartPointer<vtkXMLPolyDataWriter>::New();
    writer->SetFileName(path.c_str());
    writer->SetInputData(&data);
    writer->SetDataModeToAppended();
    writer->EncodeAppendedDataOff();  // raw binary
    writer->SetCompressorTypeToZLib();
    if (writer->Write() != 1 || writer->GetErrorCode() != 0)
        throw std::runtime_error("cannot write '" + path.string() + "'");
}

void CrowdRecorder::writeScene(Node& root) { write(*scenePolyData(root), "town.vtp"); }

void CrowdRecorder::record(const Crowd& crowd, const ActorProcessor& processor) {
    if (finished_) throw std::logic_error("CrowdRecorder: record() after finish()");
    const std::int64_t step = crowd.steps() > 0 ? static_cast<std::int64_t>(crowd.steps()) - 1 : 0;
    if (step == lastStep_) return;  // the same state again (a paused window)
    lastStep_ = step;
    if (step % every_ == 0) writeFrame(crowd, processor, step, crowd.time());
    // Speeds of the next written step are measured from the step before it.
    if ((step + 1) % every_ == 0) {
        last_.resize(3 * crowd.size());
        for (ActorId id = 0; id < crowd.size(); ++id) {
            const Mat4& r = crowd.referencePoint(id);
            last_[3 * id] = r[3].x, last_[3 * id + 1] = r[3].y, last_[3 * id + 2] = r[3].z;
        }
        lastTime_ = crowd.time();
    }
}

void CrowdRecorder::writeFrame(const Crowd& crowd, const ActorProcessor& processor, std::int64_t step, double time) {
    const Crowd::State& s = crowd.state();
    const std::size_t n = crowd.size();
    const auto count = static_cast<vtkIdType>(n);

    // What DRAW got of each actor: its tier and the finest vaLod level of its items.
    tier_.assign(n, kNotDrawn);
    lod_.assign(n, INT_MAX);
    for (const DrawItem& item : processor.drawList().items()) {
        if (item.actor >= n) continue;
        const Tier t = tierOf(item.representation);
        tier_[item.actor] = std::max<std::int8_t>(tier_[item.actor], t);
        if (t != kImpostor) lod_[item.actor] = std::min(lod_[item.actor], static_cast<int>(item.lodLevel));
    }

    // Groups are the nodes holding actors; templates are numbered as first met.
    std::unordered_map<const Node*, int> nodeIndex;
    groupNames_.clear();
    for (Node* node : crowd.nodes()) {
        nodeIndex.emplace(node, static_cast<int>(groupNames_.size()));
        groupNames_.push_back(node->name().empty() ? "node " + std::to_string(groupNames_.size()) : node->name());
    }
    std::unordered_map<const ActorTemplate*, int> templateIndex;
    templateNames_.clear();

    auto points = vtkSmartPointer<vtkPoints>::New();
    points->SetDataTypeToDouble();
    points->SetNumberOfPoints(count);
    auto id = namedArray<vtkIntArray>("id", count);
    auto group = namedArray<vtkIntArray>("group", count);
    auto tmpl = namedArray<vtkIntArray>("template", count);
    auto tier = namedArray<vtkIntArray>("tier", count);
    auto lod = namedArray<vtkIntArray>("lod", count);
    auto level = namedArray<vtkIntArray>("behaviour_level", count);
    auto speed = namedArray<vtkDoubleArray>("speed", count);
    auto cls = namedArray<vtkIntArray>("cascade_class", count);
    auto rejected = namedArray<vtkIntArray>("rejected_at", count);

    const WrittenFrame frame{step, time, "", n, samples_.size()};
    samples_.resize(samples_.size() + 3 * n);
    sampleSpeed_.resize(sampleSpeed_.size() + n);
    groupOf_.assign(n, -1);
    templateOf_.assign(n, -1);
    const bool haveLast = !last_.empty() && time > lastTime_;
    // Traditional processing runs no cascade: it classifies nobody.
    const bool cascade = processor.processing() == Processing::Actor;
    const double lodScale = processor.lodScale();
    for (ActorId a = 0; a < n; ++a) {
        const auto i = static_cast<vtkIdType>(a);
        const Mat4& r = crowd.referencePoint(a);
        double* p = &samples_[frame.offset + 3 * a];
        p[0] = r[3].x, p[1] = r[3].y, p[2] = r[3].z;
        points->SetPoint(i, p);
        id->SetValue(i, static_cast<int>(a));
        const auto node = nodeIndex.find(s.owner[a]);
        groupOf_[a] = node == nodeIndex.end() ? -1 : node->second;
        group->SetValue(i, groupOf_[a]);
        const auto [t, added] = templateIndex.emplace(s.tmpl[a], static_cast<int>(templateNames_.size()));
        if (added) templateNames_.push_back(s.tmpl[a]->name());
        templateOf_[a] = t->second;
        tmpl->SetValue(i, t->second);
        tier->SetValue(i, tier_[a]);
        lod->SetValue(i, tier_[a] == kNotDrawn || tier_[a] == kImpostor ? -1 : lod_[a]);
        // The level the cascade posed it at: the behaviour's band of its scaled eye distance.
        int posedLevel = -1;
        if (tier_[a] == kMesh)
            posedLevel = processor.behaviouralLod() ? s.behaviour[a]->levelFor(s.eyeDistance[a] * lodScale / s.priority[a]) : 0;
        level->SetValue(i, posedLevel);
        double v = 0.0;
        if (haveLast && 3 * a + 2 < last_.size())
            v = std::sqrt((p[0] - last_[3 * a]) * (p[0] - last_[3 * a]) + (p[1] - last_[3 * a + 1]) * (p[1] - last_[3 * a + 1]) +
                          (p[2] - last_[3 * a + 2]) * (p[2] - last_[3 * a + 2])) /
                (time - lastTime_);
        speed->SetValue(i, v);
        sampleSpeed_[frame.offset / 3 + a] = v;
        cls->SetValue(i, cascade ? static_cast<int>(s.actorClass[a]) : -1);
        rejected->SetValue(i, cascade ? rejectedAt(s.actorClass[a], tier_[a]) : -1);
    }

    auto data = vtkSmartPointer<vtkPolyData>::New();
    data->SetPoints(points);
    data->SetVerts(cells(count, [](vtkIdType) { return vtkIdType{1}; }, [](vtkIdType i, vtkIdType) { return i; }));
    for (vtkDataArray* a : {static_cast<vtkDataArray*>(id), static_cast<vtkDataArray*>(group), static_cast<vtkDataArray*>(tmpl),
                            static_cast<vtkDataArray*>(tier), static_cast<vtkDataArray*>(lod), static_cast<vtkDataArray*>(level),
                            static_cast<vtkDataArray*>(speed), static_cast<vtkDataArray*>(cls), static_cast<vtkDataArray*>(rejected)})
        data->GetPointData()->AddArray(a);
    vtkFieldData* field = data->GetFieldData();
    auto timeValue = namedArray<vtkDoubleArray>("TimeValue", 1);  // the name ParaView reads a dataset's time from
    timeValue->SetValue(0, time);
    field->AddArray(timeValue);
    auto stepValue = namedArray<vtkLongLongArray>("step", 1);
    stepValue->SetValue(0, step);
    field->AddArray(stepValue);
    field->AddArray(names("group_names", groupNames_));
    field->AddArray(names("template_names", templateNames_));
    field->AddArray(names("tier_names", kTierNames));
    field->AddArray(names("class_names", kClassNames));
    field->AddArray(names("rejected_at_names", kRejectedAtNames));

    char name[64];
    std::snprintf(name, sizeof name, "actors_%06lld.vtp", static_cast<long long>(step));
    write(*data, name);
    frames_.push_back(frame);
    frames_.back().file = name;
}

void CrowdRecorder::writeTrajectories() {
    // Actor a has a point in every written frame that held it (the crowd only grows).
    std::size_t actors = 0;
    for (const WrittenFrame& f : frames_) actors = std::max(actors, f.actors);
    std::vector<std::size_t> firstFrame(actors, frames_.size());
    for (std::size_t k = frames_.size(); k-- > 0;)
        for (std::size_t a = 0; a < frames_[k].actors; ++a) firstFrame[a] = k;
    const std::size_t pointCount = samples_.size() / 3;
    auto time = namedArray<vtkDoubleArray>("time", static_cast<vtkIdType>(pointCount));
    for (const WrittenFrame& f : frames_)
        for (std::size_t a = 0; a < f.actors; ++a) time->SetValue(static_cast<vtkIdType>(f.offset / 3 + a), f.time);
    auto speed = namedArray<vtkDoubleArray>("speed", static_cast<vtkIdType>(pointCount));
    for (std::size_t i = 0; i < pointCount; ++i) speed->SetValue(static_cast<vtkIdType>(i), sampleSpeed_[i]);

    // A line of one sample repeats it (VTK's poly data does not take a one-point line).
    auto samples = [&](vtkIdType a) { return static_cast<vtkIdType>(frames_.size() - firstFrame[std::size_t(a)]); };
    const auto lines = cells(
        static_cast<vtkIdType>(actors), [&](vtkIdType a) { return std::max<vtkIdType>(samples(a), 2); },
        [&](vtkIdType a, vtkIdType k) {
            const WrittenFrame& f = frames_[firstFrame[std::size_t(a)] + std::size_t(std::min(k, samples(a) - 1))];
            return static_cast<vtkIdType>(f.offset / 3 + std::size_t(a));
        });
    auto id = namedArray<vtkIntArray>("id", static_cast<vtkIdType>(actors));
    auto group = namedArray<vtkIntArray>("group", static_cast<vtkIdType>(actors));
    auto tmpl = namedArray<vtkIntArray>("template", static_cast<vtkIdType>(actors));
    for (std::size_t a = 0; a < actors; ++a) {
        const auto i = static_cast<vtkIdType>(a);
        id->SetValue(i, static_cast<int>(a));
        group->SetValue(i, a < groupOf_.size() ? groupOf_[a] : -1);
        tmpl->SetValue(i, a < templateOf_.size() ? templateOf_[a] : -1);
    }
    auto data = vtkSmartPointer<vtkPolyData>::New();
    data->SetPoints(doublePoints(samples_.data(), pointCount));
    data->SetLines(lines);
    data->GetPointData()->AddArray(time);
    data->GetPointData()->AddArray(speed);
    data->GetCellData()->AddArray(id);
    data->GetCellData()->AddArray(group);
    data->GetCellData()->AddArray(tmpl);
    data->GetFieldData()->AddArray(names("group_names", groupNames_));
    data->GetFieldData()->AddArray(names("template_names", templateNames_));
    write(*data, "trajectories.vtp");
}

// VTK has no writer for ParaView's .pvd collection (a short XML list of files and times): written here.
void CrowdRecorder::writeCollection() const {
    const fs::path path = directory_ / "crowd.pvd";
    std::ostringstream out;
    out << "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n  <Collection>\n";
    char line[256];
    for (const WrittenFrame& f : frames_) {
        std::snprintf(line, sizeof line, "    <DataSet timestep=\"%.17g\" group=\"\" part=\"0\" file=\"%s\"/>\n", f.time, f.file.c_str());
        out << line;
    }
    out << "  </Collection>\n</VTKFile>\n";
    writeWholeFile(path, out.str());
}

void CrowdRecorder::finish() {
    if (finished_) return;
    finished_ = true;
    writeTrajectories();
    writeCollection();
    std::vector<std::size_t> frameSizes;
    for (const WrittenFrame& f : frames_) frameSizes.push_back(f.actors);
    writeCrowdMaps(directory_, samples_, sampleSpeed_, frameSizes);
}

}  // namespace throng::vtk
