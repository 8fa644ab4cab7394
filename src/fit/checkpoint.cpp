#include "fit/checkpoint.h"

#include <cstdint>
#include <cstring>
#include <string_view>

#include "io/atomic_file.h"
#include "io/input_file.h"
#include "util/error.h"
#include "util/hash.h"

namespace subdfit::fit {
namespace {

// The last byte is the format version: a reader refuses any other.
constexpr std::string_view kMagic{"SDFTCKP9", 8};
constexpr std::string_view kMagicFamily{"SDFTCKP", 7};

class Writer {
public:
    template <class T>
    void put(const T& value) {
        bytes_.append(reinterpret_cast<const char*>(&value), sizeof(T));
    }
    void putBytes(std::string_view data) {
        put<std::uint64_t>(data.size());
        bytes_.append(data);
    }
    template <class T>
    void putArray(const std::vector<T>& values) {
        putBytes({reinterpret_cast<const char*>(values.data()), values.size() * sizeof(T)});
    }
    void putFloats(const std::vector<float>& values) { putArray(values); }
    // The payload followed by its checksum.
    std::string finish() && {
        put<std::uint64_t>(hash64(bytes_));
        return std::move(bytes_);
    }

private:
    std::string bytes_{kMagic};
};

// Every read is checked against what is left, so a damaged count can never allocate more
// than the file holds.
class Reader {
public:
    Reader(std::string_view payload, std::string path) : rest_(payload), path_(std::move(path)) {}

    template <class T>
    T get() {
        T value;
        std::memcpy(&value, take(sizeof(T)).data(), sizeof(T));
        return value;
    }
    std::string_view getBytes() { return take(get<std::uint64_t>()); }
    template <class T>
    std::vector<T> getArray() {
        const std::string_view bytes = getBytes();
        if (bytes.size() % sizeof(T) != 0) damaged("an array of " + std::to_string(bytes.size()) + " bytes");
        std::vector<T> values(bytes.size() / sizeof(T));
        std::memcpy(values.data(), bytes.data(), bytes.size());
        return values;
    }
    std::vector<float> getFloats() { return getArray<float>(); }
    bool atEnd() const { return rest_.empty(); }
    [[noreturn]] void damaged(const std::string& what) const {
        throw fileError(path_, "damaged checkpoint (" + what + "); remove it to start over");
    }

private:
    std::string_view take(std::uint64_t n) {
        if (n > rest_.size()) damaged("it ends early");
        const std::string_view bytes = rest_.substr(0, size_t(n));
        rest_.remove_prefix(size_t(n));
        return bytes;
    }

    std::string_view rest_;
    std::string path_;
};

}  // namespace

void writeCheckpoint(const std::filesystem::path& path, const std::string& fingerprint, const FitState& state) {
    Writer out;
    out.putBytes(fingerprint);
    out.put<std::int32_t>(state.steps);
    out.put<std::uint32_t>(state.samples);
    out.put<std::uint32_t>(std::uint32_t(state.groups.size()));
    for (const auto& group : state.groups) {
        out.put<std::int32_t>(group.adamSteps);
        out.putFloats(group.theta);
        out.putFloats(group.moment1);
        out.putFloats(group.moment2);
        out.put<float>(group.groupMoment2);
    }
    out.put<float>(state.learningRateScale);
    out.put<std::int32_t>(state.mapsStartStep);
    const ScheduleState& schedule = state.schedule;
    out.put<double>(schedule.bestLoss);
    out.put<std::int32_t>(schedule.bestStep);
    out.putArray(schedule.window);
    out.putArray(schedule.stageLosses);
    out.put<std::int32_t>(schedule.stageStart);
    out.put<std::uint8_t>(schedule.probationOver             ? 1
                          : schedule.probationStopsOnlyARise ? 2
                          : schedule.probationAsksAGain      ? 3
                                                             : 0);
    out.put<std::int32_t>(schedule.halvings);
    out.put<std::int32_t>(schedule.carriedHalvings);
    out.put<std::uint32_t>(std::uint32_t(schedule.bestTheta.size()));
    for (const auto& theta : schedule.bestTheta) out.putFloats(theta);
    out.put<std::uint32_t>(std::uint32_t(schedule.startTheta.size()));
    for (const auto& theta : schedule.startTheta) out.putFloats(theta);
    out.put<std::uint32_t>(std::uint32_t(state.monitored.size()));
    for (const MonitorMeasurement& m : state.monitored) {
        out.put<std::int32_t>(m.step);
        out.put<double>(m.seconds);
        out.put<double>(m.loss);
    }
    io::writeTextAtomically(path, std::move(out).finish());
}

std::optional<FitState> readCheckpoint(const std::filesystem::path& path, const std::string& fingerprint) {
    const std::string name = path.string();
    std::error_code ec;
    if (!std::filesystem::exists(path, ec)) return std::nullopt;
    const std::string bytes = io::readInputFile(path);
    const std::string_view all(bytes);
    if (all.substr(0, kMagicFamily.size()) != kMagicFamily) throw fileError(name, "not a subdfit checkpoint");
    if (all.size() < kMagic.size() || all.substr(0, kMagic.size()) != kMagic)
        throw fileError(name, "checkpoint of another format version (this subdfit reads version " +
                                  std::string(1, kMagic.back()) + "); remove it to start over");
    if (all.size() < kMagic.size() + sizeof(std::uint64_t))
        throw fileError(name, "truncated checkpoint; remove it to start over");
    const std::string_view payload = all.substr(0, all.size() - sizeof(std::uint64_t));
    std::uint64_t stored;
    std::memcpy(&stored, all.data() + payload.size(), sizeof stored);
    if (hash64(payload) != stored)
        throw fileError(name, "damaged checkpoint (its checksum does not match); remove it to start over");

    Reader in(payload.substr(kMagic.size()), name);
    if (in.getBytes() != fingerprint)
        throw fileError(name, "checkpoint was written for other inputs or settings; remove it or drop --resume");
    FitState state;
    state.steps = in.get<std::int32_t>();
    state.samples = in.get<std::uint32_t>();
    const auto groups = in.get<std::uint32_t>();
    if (state.steps < 0 || groups > 16) in.damaged("bad step or group count");
    for (std::uint32_t k = 0; k < groups; ++k) {
        GroupState group;
        group.adamSteps = in.get<std::int32_t>();
        group.theta = in.getFloats();
        group.moment1 = in.getFloats();
        group.moment2 = in.getFloats();
        group.groupMoment2 = in.get<float>();
        state.groups.push_back(std::move(group));
    }
    state.learningRateScale = in.get<float>();
    state.mapsStartStep = in.get<std::int32_t>();
    ScheduleState& schedule = state.schedule;
    schedule.bestLoss = in.get<double>();
    schedule.bestStep = in.get<std::int32_t>();
    schedule.window = in.getArray<double>();
    schedule.stageLosses = in.getArray<double>();
    schedule.stageStart = in.get<std::int32_t>();
    const auto probation = in.get<std::uint8_t>();
    if (probation > 3) in.damaged("bad probation state");
    schedule.probationOver = probation == 1;
    schedule.probationStopsOnlyARise = probation == 2;
    schedule.probationAsksAGain = probation == 3;
    schedule.halvings = in.get<std::int32_t>();
    schedule.carriedHalvings = in.get<std::int32_t>();
    if (schedule.halvings < 0 || schedule.carriedHalvings < 0) in.damaged("bad halving count");
    const auto bestGroups = in.get<std::uint32_t>();
    if (bestGroups > groups) in.damaged("bad best-state group count");
    for (std::uint32_t k = 0; k < bestGroups; ++k) schedule.bestTheta.push_back(in.getFloats());
    const auto startGroups = in.get<std::uint32_t>();
    if (startGroups > groups) in.damaged("bad start-state group count");
    for (std::uint32_t k = 0; k < startGroups; ++k) schedule.startTheta.push_back(in.getFloats());
    const auto measurements = in.get<std::uint32_t>();
    for (std::uint32_t k = 0; k < measurements; ++k) {
        MonitorMeasurement m;
        m.step = in.get<std::int32_t>();
        m.seconds = in.get<double>();
        m.loss = in.get<double>();
        state.monitored.push_back(m);
    }
    if (!in.atEnd()) in.damaged("bytes after the monitored losses");
    return state;
}

}  // namespace subdfit::fit
