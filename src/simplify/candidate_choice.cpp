#include "simplify/candidate_choice.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <numeric>

#include "fit/fit_run.h"
#include "util/interrupt.h"

namespace subdfit::simplify {
namespace {

// The training views in settling order: a stride through them, so that each block looks from
// all around rather than from one band of the orbit.
std::vector<int> settlingOrder(int views) {
    std::vector<int> order;
    int stride = std::max(1, int(std::lround(0.618 * views)));
    while (std::gcd(stride, views) != 1) ++stride;
    for (int k = 0; k < views; ++k) order.push_back(int((std::int64_t(k) * stride) % views));
    return order;
}

// The loss over the monitor views and the first `views` training views drawn.
double settledLossOf(const Fitting& f, int monitorViews, size_t views) {
    double sum = f.candidate.monitorLoss * monitorViews;
    for (size_t v = 0; v < views; ++v) sum += f.trainingLoss[v];
    return sum / double(monitorViews + int(views));
}

// Whether the lowest of `near` on the first `views` training views leads each other clearly
// (kClearlyAhead standard errors of their view-for-view differences, beyond kLossTolerance for
// one of fewer bytes): then more views would not change what preferred() chooses.
bool clearlyAhead(const std::vector<Fitting*>& near, int monitorViews, size_t views) {
    if (views < 2 * size_t(kSettleBlock)) return false;
    const Fitting* leader = *std::min_element(near.begin(), near.end(), [&](const Fitting* a, const Fitting* b) {
        return settledLossOf(*a, monitorViews, views) < settledLossOf(*b, monitorViews, views);
    });
    const double tolerance = kLossTolerance * settledLossOf(*leader, monitorViews, views);
    return std::all_of(near.begin(), near.end(), [&](const Fitting* f) {
        if (f == leader) return true;
        const double margin = f->candidate.bytes < leader->candidate.bytes ? tolerance : 0.0;
        double sum = 0.0, squares = 0.0;
        for (size_t v = 0; v < views; ++v) {
            const double d = f->trainingLoss[v] - leader->trainingLoss[v];
            sum += d;
            squares += d * d;
        }
        const double n = double(views), mean = sum / n;
        const double standardError = std::sqrt(std::max(0.0, squares / n - mean * mean) / (n - 1.0));
        return mean - kClearlyAhead * standardError > margin;
    });
}

}  // namespace

double monitored(const BudgetCandidate& c) { return c.monitorLoss; }
double settled(const BudgetCandidate& c) { return c.settledLoss; }

const Fitting* lowestOf(const std::vector<Fitting>& fitting, const Keep& keep, LossOf loss) {
    const Fitting* lowest = nullptr;
    for (const Fitting& f : fitting)
        if (keep(f.candidate) && (!lowest || loss(f.candidate) < loss(lowest->candidate))) lowest = &f;
    return lowest;
}

const Fitting* preferred(const std::vector<Fitting>& fitting, const Keep& keep, LossOf loss) {
    const Fitting* lowest = lowestOf(fitting, keep, loss);
    if (!lowest) return nullptr;
    const double lowestLoss = loss(lowest->candidate), bytes = double(lowest->candidate.bytes);
    const Fitting* best = lowest;
    for (const Fitting& f : fitting) {
        const double lossGivenUp = loss(f.candidate) / lowestLoss - 1.0,
                     bytesSaved = 1.0 - double(f.candidate.bytes) / bytes;
        if (keep(f.candidate) && lossGivenUp <= kLossTolerance && bytesSaved >= kBytesPerLoss * lossGivenUp &&
            f.candidate.bytes < best->candidate.bytes)
            best = &f;
    }
    return best;
}

SettlingViews::SettlingViews(gl::ProgramCache& programs, const fit::FitScene& scene)
    : programs_(programs), scene_(scene), order_(settlingOrder(scene.training.size())) {}

double SettlingViews::loss(fit::CageFitter& fitter, size_t v) {
    const scene::TargetSet& views = block(v / kSettleBlock);
    const int k = int(v % kSettleBlock);
    return views.loss(
        k, [&](const render::Camera& camera, const render::RenderTarget& canvas) { fitter.render(camera, canvas); });
}

const scene::TargetSet& SettlingViews::block(size_t b) {
    if (!block_ || blockIndex_ != b) {
        block_.reset();
        std::vector<render::Camera> cameras;
        for (size_t v = b * kSettleBlock; v < std::min(order_.size(), (b + 1) * kSettleBlock); ++v)
            cameras.push_back(scene_.training.camera(order_[v]));
        block_.emplace(programs_, scene_.referenceRenderer, std::move(cameras), scene_.training.resolution(),
                       fit::kViewerSupersampling);
        blockIndex_ = b;
    }
    return *block_;
}

const Fitting* settle(gl::ProgramCache& programs, const fit::FitScene& scene, SettlingViews& settling,
                      std::vector<Fitting>& fitting, const Keep& keep) {
    const Fitting* lowest = lowestOf(fitting, keep, monitored);
    if (!lowest) return nullptr;
    const double within = (1.0 + kNearTie) * lowest->candidate.monitorLoss;
    std::vector<Fitting*> near;
    for (Fitting& f : fitting)
        if (keep(f.candidate) && f.candidate.monitorLoss <= within) near.push_back(&f);
    if (near.size() == 1) return lowest;
    std::map<const Fitting*, std::unique_ptr<fit::CageFitter>> drawn;
    size_t views = 0;
    while (views < settling.size() && !clearlyAhead(near, scene.monitor.size(), views)) {
        views = std::min(settling.size(), views + size_t(kSettleBlock));
        for (Fitting* f : near)
            for (size_t v = f->trainingLoss.size(); v < views; ++v) {
                throwIfStopRequested();
                auto& fitter = drawn[f];
                if (!fitter)
                    fitter = drawnAsFitted(programs, scene, codec::decodeSubd(*f->encoded, "budget candidate"));
                f->trainingLoss.push_back(settling.loss(*fitter, v));
            }
    }
    for (Fitting* f : near) {
        f->candidate.settledLoss = settledLossOf(*f, scene.monitor.size(), views);
        f->candidate.settledViews = int(views);
    }
    return preferred(
        fitting, [&](const BudgetCandidate& c) { return keep(c) && c.monitorLoss <= within; }, settled);
}

}  // namespace subdfit::simplify
