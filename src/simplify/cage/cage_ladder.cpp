#include "simplify/cage/cage_ladder.h"

#include <algorithm>

#include "util/error.h"
#include "util/interrupt.h"

namespace subdfit::simplify {

namespace {

// One builder per 4 cores, at most 4: the limit fits' rays already use every core, and each
// builder holds a decimation of the reference.
unsigned buildersFor(unsigned cores, size_t rungs) {
    return unsigned(std::clamp<size_t>(cores / 4, 1, std::min<size_t>(4, std::max<size_t>(rungs, 1))));
}

}  // namespace

CageLadder::CageLadder(const mesh::PolygonMesh& reference, std::vector<int> faceCounts, CageShape shape,
                       Prepare prepare, unsigned builders)
    : shape_(shape), promises_(faceCounts.size()), built_(faceCounts.size(), 0) {
    for (auto& promise : promises_) cages_.push_back(promise.get_future());
    if (builders == 0) builders = buildersFor(std::thread::hardware_concurrency(), faceCounts.size());
    builder_ = std::thread([this, &reference, counts = std::move(faceCounts), prepare = std::move(prepare), builders] {
        build(reference, counts, prepare, builders);
    });
}

CageLadder::~CageLadder() {
    stop_ = true;
    releaseRunAhead();
    if (builder_.joinable()) builder_.join();
}

void CageLadder::build(const mesh::PolygonMesh& reference, const std::vector<int>& faceCounts, const Prepare& prepare,
                       unsigned builders) {
    try {
        source_.emplace(reference, true,
                        faceCounts.empty() ? 0 : *std::max_element(faceCounts.begin(), faceCounts.end()));
        std::vector<std::jthread> helpers;
        for (unsigned h = 1; h < builders; ++h) helpers.emplace_back([&] { buildRungs(faceCounts, prepare); });
        buildRungs(faceCounts, prepare);
    } catch (...) {
        // The source failed: every cage waited for reports it.
        for (size_t k = 0; k < promises_.size(); ++k)
            if (!built_[k]) promises_[k].set_exception(std::current_exception());
        return;
    }
    // Building stopped early (interrupted, a rung failed, or the ladder is going): a rung never
    // begun says so rather than leave its taker waiting.
    for (size_t k = 0; k < promises_.size(); ++k)
        if (!built_[k])
            promises_[k].set_exception(std::make_exception_ptr(
                Error("the cage of " + std::to_string(faceCounts[k]) + " faces was not built: building stopped")));
}

void CageLadder::buildRungs(const std::vector<int>& faceCounts, const Prepare& prepare) {
    for (size_t k = next_++; k < faceCounts.size() && mayBuild(k); k = next_++) {
        try {
            mesh::PolygonMesh cage = source_->cage({.faces = faceCounts[k], .shape = shape_});
            if (prepare) prepare(cage);
            promises_[k].set_value(std::move(cage));
        } catch (const Interrupted&) {
            promises_[k].set_exception(std::current_exception());
            stop_ = true;
        } catch (const Error&) {
            promises_[k].set_value(std::nullopt);  // too few faces survive: the caller goes on
        } catch (...) {
            // The cage waited for reports it, and the others stop.
            promises_[k].set_exception(std::current_exception());
            stop_ = true;
        }
        built_[k] = 1;
    }
}

bool CageLadder::mayBuild(size_t k) {
    std::unique_lock lock(takenMutex_);
    takenChanged_.wait(lock, [&] { return stop_ || runAhead_ || k < taken_ + kRunAhead; });
    return !stop_;
}

void CageLadder::releaseRunAhead() {
    {
        const std::lock_guard lock(takenMutex_);
        runAhead_ = true;
    }
    takenChanged_.notify_all();
}

std::optional<mesh::PolygonMesh> CageLadder::take(size_t k) {
    {
        const std::lock_guard lock(takenMutex_);
        taken_ = std::max(taken_, k + 1);
    }
    takenChanged_.notify_all();
    return cages_.at(k).get();
}

const CageSource& CageLadder::source() {
    releaseRunAhead();
    if (builder_.joinable()) builder_.join();
    if (!source_) throw Error("the cage ladder has no source: preparing the reference failed");
    return *source_;
}

}  // namespace subdfit::simplify
