#pragma once
// Which of the budget search's candidates ships: the lowest loss on the choosing views, fewer
// bytes where the loss given up is within the monitor's noise, and near ties settled on the
// training cameras drawn as a viewer sees them.
#include <cstddef>
#include <functional>
#include <memory>
#include <optional>
#include <vector>

#include "codec/subd_format.h"
#include "fit/cage_fitter.h"
#include "fit/fit_scene.h"
#include "gl/program_cache.h"
#include "mesh/polygon_mesh.h"
#include "simplify/budget_candidate.h"
#include "simplify/compare/quality.h"

namespace subdfit::simplify {

// Within this fraction of the lowest monitor loss, fewer bytes win: a difference that small is
// within the monitor's own noise ...
inline constexpr double kLossTolerance = 0.02;
// ... but only where the bytes saved are worth it: at least this many times the loss given up,
// both relative (a few bytes saved are not worth a loss near the tolerance).
inline constexpr double kBytesPerLoss = 5.0;
// Four monitor views rank candidates this close to the lowest no better than chance: those
// within this fraction are scored again from the training cameras too (supersampled as those
// are), and the choice among them is made on that score.
inline constexpr double kNearTie = 0.2;
// The training views are drawn in blocks of this many, and the settling ends once the choice is
// clear: the leader's loss below every other candidate's, view for view, by this many standard
// errors, and by kLossTolerance more for a candidate of fewer bytes (which preferred() would
// otherwise take).
inline constexpr int kSettleBlock = 4;
inline constexpr double kClearlyAhead = 3.0;

// A candidate within the budget, the cage it was built on and its asset as shipped.
struct Fitting {
    BudgetCandidate candidate;
    std::shared_ptr<const mesh::PolygonMesh> cageWorld;
    std::shared_ptr<const std::vector<unsigned char>> encoded;
    size_t tried;                        // its place in Findings::tried
    std::vector<double> trainingLoss{};  // on the training views drawn so far, in settling order
};

using Keep = std::function<bool(const BudgetCandidate&)>;
using LossOf = double (*)(const BudgetCandidate&);
double monitored(const BudgetCandidate& c);  // its loss on the choosing views
double settled(const BudgetCandidate& c);    // on those and the training cameras settle() drew

// Of those `keep` accepts, the one of lowest `loss` (none if it accepts none).
const Fitting* lowestOf(const std::vector<Fitting>& fitting, const Keep& keep, LossOf loss);

// Of those `keep` accepts, the fewest bytes within kLossTolerance of the lowest `loss` that save
// kBytesPerLoss times the loss they give up.
const Fitting* preferred(const std::vector<Fitting>& fitting, const Keep& keep, LossOf loss);

// The training cameras drawn as `choosing` is (fit::kViewerSupersampling), in settling order, a
// block of kSettleBlock at a time as the settling asks for them: most settlings end within a few
// blocks, and the reference drawn supersampled from every camera would cost more than they do.
// One block is kept (its targets and its supersampled canvas): the settling draws every near
// candidate from the newest block before the next.
class SettlingViews {
public:
    SettlingViews(gl::ProgramCache& programs, const fit::FitScene& scene);

    size_t size() const { return order_.size(); }

    // The loss of what `fitter` draws from the v-th camera in settling order.
    double loss(fit::CageFitter& fitter, size_t v);

private:
    const scene::TargetSet& block(size_t b);

    gl::ProgramCache& programs_;
    const fit::FitScene& scene_;
    std::vector<int> order_;
    std::optional<scene::TargetSet> block_;
    size_t blockIndex_ = 0;
};

// preferred() among those `keep` accepts within kNearTie of the lowest monitor loss, on their
// loss over the monitor and training cameras (`views`). The cameras are drawn a block at a time,
// each near candidate from the same ones, until one clearly leads or all are drawn. A lone
// leader has no tie to settle: it is chosen as it is.
const Fitting* settle(gl::ProgramCache& programs, const fit::FitScene& scene, SettlingViews& settling,
                      std::vector<Fitting>& fitting, const Keep& keep);

}  // namespace subdfit::simplify
