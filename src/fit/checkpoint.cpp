#include "fit/checkpoint.h"

#include <cstdint>
#include <fstream>

#include "io/atomic_file.h"
#include "util/error.h"

namespace subdfit::fit {
namespace {

constexpr char kMagic[8] = {'S', 'D', 'F', 'T', 'C', 'K', 'P', '2'};

template <class T>
void put(std::ostream& out, const T& value) {
    out.write(reinterpret_cast<const char*>(&value), sizeof(T));
}

template <class T>
T get(std::istream& in) {
    T value{};
    in.read(reinterpret_cast<char*>(&value), sizeof(T));
    return value;
}

void putFloats(std::ostream& out, const std::vector<float>& values) {
    put<std::uint64_t>(out, values.size());
    out.write(reinterpret_cast<const char*>(values.data()), std::streamsize(values.size() * sizeof(float)));
}

std::vector<float> getFloats(std::istream& in, std::uint64_t limit) {
    const auto count = get<std::uint64_t>(in);
    if (!in || count > limit) return {};
    std::vector<float> values(count);
    in.read(reinterpret_cast<char*>(values.data()), std::streamsize(count * sizeof(float)));
    return values;
}

}  // namespace

void writeCheckpoint(const std::filesystem::path& path, const std::string& fingerprint,
                     const CageFitter::State& state) {
    io::writeAtomically(path, [&](const std::filesystem::path& temporary) {
        std::ofstream out(temporary, std::ios::binary);
        out.write(kMagic, sizeof(kMagic));
        put<std::uint64_t>(out, fingerprint.size());
        out.write(fingerprint.data(), std::streamsize(fingerprint.size()));
        put<std::int32_t>(out, state.steps);
        put<std::uint32_t>(out, state.samples);
        put<std::uint32_t>(out, std::uint32_t(state.groups.size()));
        for (const auto& group : state.groups) {
            put<std::int32_t>(out, group.adamSteps);
            putFloats(out, group.theta);
            putFloats(out, group.moment1);
            putFloats(out, group.moment2);
        }
        out.close();
        if (!out) throw fileError(path.string(), "could not write checkpoint");
    });
}

std::optional<CageFitter::State> readCheckpoint(const std::filesystem::path& path, const std::string& fingerprint) {
    if (!std::filesystem::exists(path)) return std::nullopt;
    std::ifstream in(path, std::ios::binary);
    char magic[sizeof(kMagic)] = {};
    in.read(magic, sizeof(magic));
    if (!in || !std::equal(magic, magic + sizeof(magic), kMagic)) throw fileError(path.string(), "not a subdfit checkpoint");
    const auto length = get<std::uint64_t>(in);
    if (!in || length > (1u << 20)) throw fileError(path.string(), "damaged checkpoint header");
    std::string stored(length, '\0');
    in.read(stored.data(), std::streamsize(length));
    if (stored != fingerprint)
        throw fileError(path.string(), "checkpoint was written for other inputs or settings; remove it or drop --resume");
    CageFitter::State state;
    state.steps = get<std::int32_t>(in);
    state.samples = get<std::uint32_t>(in);
    const auto groups = get<std::uint32_t>(in);
    if (!in || state.steps < 0 || groups > 16) throw fileError(path.string(), "damaged checkpoint");
    const std::uint64_t limit = std::uint64_t(1) << 32;
    for (std::uint32_t k = 0; k < groups; ++k) {
        CageFitter::GroupState group;
        group.adamSteps = get<std::int32_t>(in);
        group.theta = getFloats(in, limit);
        group.moment1 = getFloats(in, limit);
        group.moment2 = getFloats(in, limit);
        state.groups.push_back(std::move(group));
    }
    if (!in) throw fileError(path.string(), "truncated checkpoint");
    return state;
}

}  // namespace subdfit::fit
