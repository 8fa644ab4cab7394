#include "fit/fit_run.h"

#include <algorithm>
#include <cmath>
#include <optional>

#include "fit/asset_export.h"
#include "fit/checkpoint.h"
#include "io/image_io.h"
#include "mesh/obj_writer.h"
#include "util/error.h"

namespace subdfit::fit {

void writeMaps(CageFitter& fitter, const surface::SurfaceMaps& maps) {
    auto* parameters = fitter.maps();
    if (!parameters) return;
    for (const kinds::MapKindInfo& kind : kinds::kMapKinds)
        if (optim::ParameterGroup* group = parameters->group(kind.kind); group && maps.has(kind.kind))
            group->write(maps.values(kind.kind));
    if (maps.appearanceAtlas.present() && parameters->appearanceAtlas().present())
        parameters->setAppearanceUvs(maps.appearanceAtlas.cornerUvs);
    if (parameters->effects().appearance() && maps.kinds().appearance()) parameters->setCarriedTextures(maps);
}

}  // namespace subdfit::fit

namespace subdfit::fit {
namespace {

using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

// Every parameter of every group, maps included.
bool allFinite(CageFitter& fitter) {
    for (auto* group : fitter.groups())
        for (float value : group->read())
            if (!std::isfinite(value)) return false;
    return true;
}

// Parameters only: what a best state needs to be returned to.
std::vector<std::vector<float>> readTheta(CageFitter& fitter) {
    std::vector<std::vector<float>> theta;
    for (auto* group : fitter.groups()) theta.push_back(group->read());
    return theta;
}

// How much worse than the best the monitored loss must be for a halving to return to the best.
constexpr double kRestoreAbove = 1.5;

}  // namespace

const char* toString(StopReason reason) {
    switch (reason) {
        case StopReason::Reached: return "steps";
        case StopReason::Converged: return "converged";
        case StopReason::NoGain: return "no_gain";
        case StopReason::Cancelled: return "interrupted";
    }
    return "steps";
}

FitRun::FitRun(const ResolvedFitOptions& options, gl::ProgramCache& programs, FitScene& scene, ReportScores scores)
    : options_(*options),
      programs_(programs),
      scene_(scene),
      fitter_(std::make_unique<CageFitter>(programs, scene.cage, fitSettings(options_, scene.cage, scene.shading))),
      fingerprint_(checkpointFingerprint(options_, scene.cage, scene.reference)),
      monitorEvery_(std::clamp(options_.steps / 50, 5, 10)),
      started_(Clock::now()),
      scores_(scores) {}

void FitRun::scoreStart() {
    if (scores_ == ReportScores::TrainingAndHoldout) trainBefore_ = score(*fitter_, scene_.training);
    holdoutBefore_ = scoreHoldout(*fitter_, scene_.holdout);
    scoredTheta_ = readTheta(*fitter_);
    startScored_ = true;
}

// The start is scored when the first step is about to leave it, not when the run is made: maps
// a stage bakes in (startFrom) would make a score of the bare cage a render thrown away.
void FitRun::scoreStartOnce() {
    if (!startScored_) scoreStart();
}

void FitRun::startFrom(const surface::SurfaceMaps& maps) {
    SUBDFIT_CHECK(step() == 0);
    writeMaps(*fitter_, maps);
    mapsGiven_ = true;
    startScored_ = false;
}

bool FitRun::resume(const std::filesystem::path& checkpoint) {
    const auto saved = readCheckpoint(checkpoint, fingerprint_);
    if (!saved) return false;
    scoreStartOnce();  // the run's start, not the checkpoint's state
    try {
        fitter_->restore(*saved);
    } catch (const Error& e) {
        throw fileError(checkpoint.string(), e.what());
    }
    resumedFromStep_ = saved->steps;
    monitored_ = saved->monitored;
    fitSecondsBefore_ = monitored_.empty() ? 0.0 : monitored_.back().seconds;
    scoredTheta_.clear();  // what the caller sets after a resume (carried textures) was not drawn
    schedule_ = saved->schedule;
    if (options_.schedule == Schedule::Plateau) applyStep();
    return true;
}

void FitRun::saveCheckpoint(const std::filesystem::path& checkpoint) {
    std::filesystem::create_directories(checkpoint.parent_path());
    FitState state = fitter_->state();
    state.schedule = schedule_;
    state.monitored = monitored_;
    writeCheckpoint(checkpoint, fingerprint_, state);
}

void FitRun::advance(bool measureLoss) {
    scoreStartOnce();
    const auto began = Clock::now();
    const auto views = viewsForStep(options_, step());
    for (int sample = 0; sample < options_.samplesPerStep; ++sample)
        fitter_->accumulate(scene_.training, views, measureLoss);
    fitter_->update();
    fitSeconds_ += secondsSince(began);
}

// The schedule judges a step by its loss on the monitor views, the start included: the
// kept state is never worse than where the stage began. Returns why the stage ends, if it does.
std::optional<StopReason> FitRun::monitor(StepSchedule& schedule, const FitHooks& hooks) {
    const double monitorLoss = score(*fitter_, scene_.monitor).loss;
    monitored_.push_back({step(), fitSecondsBefore_ + fitSeconds_, monitorLoss});
    const bool first = schedule_.stageStart < 0;
    const StepSchedule::Decision decision = schedule.record(monitorLoss, step());
    if (decision.best) schedule_.bestTheta = readTheta(*fitter_);
    if (first) schedule_.startTheta = readTheta(*fitter_);
    if (decision.action == StepSchedule::Action::Halve) {
        // Clearly worse than the best (not only noisier): back to the best state, with the
        // smaller step. A start that was already close (a limit-interpolated cage, baked
        // maps) is not left where too large a step took it, which can take hundreds of steps
        // to come back from.
        if (monitorLoss > kRestoreAbove * schedule_.bestLoss) restoreBest();
        applyStep();
    }
    const bool risingLate = schedule_.probationAsksAGain && !schedule_.probationOver && schedule.clearlyRose();
    if (!schedule_.probationOver && (step() - schedule_.stageStart >= probationSteps() || risingLate))
        if (const auto ended = endProbation(schedule, hooks, risingLate)) return ended;
    const int lastJudged = judged_.stageStart == schedule_.stageStart ? judged_.lastJudged : schedule_.stageStart;
    if (hooks.judge && schedule_.probationOver && step() - lastJudged >= kJudgeEvery &&
        judgeTheBest(hooks) >= kJudgedWorse) {
        takeTheJudgedBest();
        if (hooks.note)
            hooks.note("the monitor's best has not improved on the judging views in " +
                       std::to_string(step() - judged_.step) + " steps: the stage stops (stop_reason converged)");
        return StopReason::Converged;
    }
    if (hooks.judge && schedule_.probationOver && schedule_.bestStep >= 0 &&
        step() - schedule_.bestStep >= kStalledSteps) {
        if (judgeTheBest(hooks) > 0) takeTheJudgedBest();
        else restoreBest();
        if (hooks.note)
            hooks.note("the monitor's best has not improved in " + std::to_string(step() - schedule_.bestStep) +
                       " steps: the stage stops (stop_reason converged)");
        return StopReason::Converged;
    }
    if (decision.action == StepSchedule::Action::Converged) return StopReason::Converged;
    return std::nullopt;
}

// The end of the stage's probation: whether the steps pay, and if not, why the stage ends.
std::optional<StopReason> FitRun::endProbation(StepSchedule& schedule, const FitHooks& hooks, bool rising) {
    schedule_.probationOver = true;
    const StepSchedule::Verdict verdict = rising ? StepSchedule::Verdict::NoGain : schedule.probation();
    if (verdict == StepSchedule::Verdict::StepTooLarge) {
        const int stageSteps = step() - schedule_.stageStart;
        restoreBest();
        schedule.retryFromBest(step());
        applyStep();
        if (hooks.note)
            hooks.note("the start gained and then lost it in " + std::to_string(stageSteps) +
                       " steps: the step is halved, on probation again from the best state");
    } else if (verdict == StepSchedule::Verdict::Paying && schedule_.probationStopsOnlyARise) {
        // A start that lay flat must have gained by kLateProbation times as many steps.
        schedule_.probationStopsOnlyARise = false;
        schedule_.probationAsksAGain = true;
        schedule_.probationOver = false;
    } else if (verdict == StepSchedule::Verdict::Paying && hooks.judge && judgeTheBest(hooks) > 0) {
        // The monitor's gain is not the judge's: the stage ends where it started.
        takeTheJudgedBest();
        if (hooks.note)
            hooks.note("the monitor's gain in " + std::to_string(step() - schedule_.stageStart) +
                       " steps is a loss on the judging views: the stage stops (stop_reason no_gain)");
        return StopReason::NoGain;
    } else if (verdict == StepSchedule::Verdict::NoGain) {
        // A best found on a first probation is the noise's pick (the monitor views are
        // few): the stage ends where it started, never below it on other views. The later
        // one keeps its best, as a stage that converged would.
        if (!schedule_.probationAsksAGain) {
            schedule_.bestTheta = schedule_.startTheta;
            schedule_.bestLoss = schedule_.stageLosses.front();
            schedule_.bestStep = schedule_.stageStart;
        }
        restoreBest();
        if (hooks.note)
            hooks.note((schedule_.probationStopsOnlyARise || rising ? "the steps made the start worse in "
                                                                    : "no gain on the start in ") +
                       std::to_string(step() - schedule_.stageStart) +
                       " steps, and none likely: the stage stops (stop_reason no_gain)");
        return StopReason::NoGain;
    }
    return std::nullopt;
}

StopReason FitRun::runTo(int until, const std::filesystem::path& checkpoint, const FitHooks& hooks) {
    until = std::min(until, options_.steps);
    const int first = step();
    const auto began = Clock::now();
    const int reportEvery = std::max(1, options_.steps / 50);
    const bool plateau = options_.schedule == Schedule::Plateau;
    StepSchedule schedule(schedule_, windowDoublings_);
    if (plateau && schedule_.bestStep < 0) {
        applyStep();
        monitor(schedule, hooks);
    }
    stopReason_ = StopReason::Reached;
    while (step() < until) {
        if (hooks.cancel && hooks.cancel->load()) {
            stopReason_ = StopReason::Cancelled;
            break;
        }
        // The loss is only read for progress, so about eight steps per report measure it.
        advance(step() % std::max(1, reportEvery / 8) == 0);
        const int taken = step();
        if (hooks.progress && (taken % reportEvery == 0 || taken == options_.steps)) {
            const double seconds = secondsSince(began);
            const double eta = seconds / double(taken - first) * double(options_.steps - taken);
            hooks.progress({taken, options_.steps, fitter_->takeMeanLoss(), seconds, eta});
        }
        // On probation the monitor looks more often: a start that cannot pay is let go early.
        if (plateau &&
            taken % (schedule_.probationOver || schedule_.probationAsksAGain ? monitorEvery_ : kProbationEvery) == 0)
            if (const auto ended = monitor(schedule, hooks)) {
                stopReason_ = *ended;
                break;
            }
        if (taken % options_.checkpointEvery == 0) saveCheckpoint(checkpoint);
    }
    saveCheckpoint(checkpoint);
    return stopReason_;
}

void FitRun::joinMaps(const MapStage& stage, bool fresh) {
    maps::MapParameters* parameters = fitter_->maps();
    if (fresh && stage.startFrom) {
        mesh::PolygonMesh current = scene_.cage;
        current.positions = fitter_->vertices();
        const surface::SurfaceMaps start = stage.startFrom(current);
        // Made before the first step, it is where the fit starts: the report's start is scored
        // on it, so that the fit's gain reads as its own, not the start's.
        if (step() == 0) startFrom(start);
        else writeMaps(*fitter_, start);
    }
    if (stage.freezeCage) fitter_->setOptimised(fitter_->vertexGroup(), false);
    for (optim::ParameterGroup* g : parameters->groups()) {
        const bool appearance = parameters->inAppearance(*g);
        fitter_->setRates(*g, g->settings().epsilon,
                          (appearance ? stage.appearanceRate : stage.geometricRate) * g->settings().learningRate);
        if (stage.noiseGate) g->settings().noiseGate = *stage.noiseGate;
    }
}

StopReason FitRun::run(const std::filesystem::path& checkpoint, const FitHooks& hooks, const MapStage& maps) {
    if (fitter_->maps()) {
        const bool pastStart = step() > fitter_->mapsStartStep();
        const StopReason cage = runTo(fitter_->mapsStartStep(), checkpoint, hooks);
        if (cage == StopReason::Cancelled) return cage;
        if (!pastStart) {
            // The cage goes on beside the maps: at the full step again it would undo, while the
            // maps start, what its last halvings settled.
            endJudgedStage(hooks);
            endStage(/*keepStep=*/true);
            if (step() < fitter_->mapsStartStep()) fitter_->startMapsNow();  // the cage converged early
            // Maps that join from zero are a poor start, not a near-optimal one the fit may fail
            // to improve: their stage has no probation (while they rise from zero the loss is flat).
            if (!mapsGiven_) schedule_.probationOver = true;
        }
        const bool givenBefore = mapsGiven_;
        joinMaps(maps, !pastStart);
        // Heights that a stage's startFrom bakes as they join start near their optimum, but their loss can
        // lie flat for dozens of steps before it falls (docs/optimizer.md): their probation stops
        // only a start the steps clearly make worse, and a later one (kLateProbation) a start
        // they have not improved by then. Maps given before the run keep the full one.
        if (!pastStart && mapsGiven_ && !givenBefore) {
            schedule_.probationOver = false;
            schedule_.probationStopsOnlyARise = true;
        }
    }
    const StopReason last = runTo(options_.steps, checkpoint, hooks);
    if (last != StopReason::Cancelled) {
        endJudgedStage(hooks);
        endStage();
    }
    return last;
}

int FitRun::probationSteps() const {
    const int stageSteps = options_.steps - std::max(0, schedule_.stageStart);
    const int share = int(std::ceil(kProbation * stageSteps));
    const int steps = std::max(2 * kProbationEvery, std::min(share, kProbationMeasurements * kProbationEvery));
    return schedule_.probationAsksAGain ? kLateProbation * steps : steps;
}

void FitRun::writeTheta(const std::vector<std::vector<float>>& theta) {
    const auto groups = fitter_->groups();
    for (size_t k = 0; k < groups.size() && k < theta.size(); ++k) groups[k]->write(theta[k]);
}

void FitRun::restoreBest() { writeTheta(schedule_.bestTheta); }

double FitRun::judgeOf(const std::vector<std::vector<float>>& theta, const FitHooks& hooks) {
    const auto current = readTheta(*fitter_);
    if (theta == current) return hooks.judge();
    writeTheta(theta);
    const double loss = hooks.judge();
    writeTheta(current);
    return loss;
}

int FitRun::judgeTheBest(const FitHooks& hooks) {
    if (judged_.stageStart != schedule_.stageStart)
        judged_ = {.stageStart = schedule_.stageStart,
                   .loss = judgeOf(schedule_.startTheta, hooks),
                   .monitorLoss = schedule_.stageLosses.front(),
                   .step = schedule_.stageStart,
                   .theta = schedule_.startTheta};
    judged_.lastJudged = step();
    if (schedule_.bestStep == judged_.step) return judged_.worseInARow;
    const double loss = judgeOf(schedule_.bestTheta, hooks);
    if (loss < judged_.loss) {
        judged_ = {.stageStart = judged_.stageStart,
                   .loss = loss,
                   .monitorLoss = schedule_.bestLoss,
                   .step = schedule_.bestStep,
                   .theta = schedule_.bestTheta,
                   .lastJudged = step()};
        return 0;
    }
    return ++judged_.worseInARow;
}

void FitRun::takeTheJudgedBest() {
    schedule_.bestTheta = judged_.theta;
    schedule_.bestLoss = judged_.monitorLoss;
    schedule_.bestStep = judged_.step;
    restoreBest();
}

void FitRun::endJudgedStage(const FitHooks& hooks) {
    if (hooks.judge && judged_.stageStart == schedule_.stageStart && !schedule_.bestTheta.empty() &&
        judgeTheBest(hooks) > 0)
        takeTheJudgedBest();
}

void FitRun::endStage(bool keepStep) {
    if (options_.schedule != Schedule::Plateau || schedule_.bestTheta.empty()) return;
    // Measured once more (unless it is the best state itself): the last steps may have been
    // better than any monitored before.
    if (readTheta(*fitter_) != schedule_.bestTheta && !(score(*fitter_, scene_.monitor).loss <= schedule_.bestLoss))
        restoreBest();
    bestStep_ = schedule_.bestStep;
    // The cage keeps its step as halvings carried; the stage's own schedule (the maps') starts at
    // the full step with every halving still to come.
    const int carried = keepStep ? schedule_.halvings + schedule_.carriedHalvings : 0;
    StepSchedule(schedule_).restart();
    schedule_.carriedHalvings = carried;
    applyStep();
}

void FitRun::applyStep() {
    const StepSchedule schedule(schedule_);
    fitter_->setLearningRateScale(schedule.learningRateScale());
    fitter_->setVertexRateFactor(schedule.vertexRateScale() / schedule.learningRateScale());
}

mesh::PolygonMesh FitRun::fittedWorld() const {
    mesh::PolygonMesh world = scene_.cageWorld;
    world.positions = scene_.frame.toWorld(fitter_->vertices());
    return world;
}

codec::SubdAsset FitRun::shippable() {
    return shippableState(options_, *fitter_, scene_.frame, fittedWorld(), std::uint32_t(scene_.reference.faceCount()));
}

std::vector<unsigned char> FitRun::coded() { return codec::encodeSubd(shippable(), subdPrecision(options_)); }

FitReport FitRun::writeResults(const std::filesystem::path& out, const context::GlContext& context) {
    scoreStartOnce();
    FitReport r;
    r.options = options_;
    r.steps = step();
    r.resumedFromStep = resumedFromStep_;
    r.fitSeconds = fitSeconds_;
    r.monitored = monitored_;
    r.trainBefore = trainBefore_;
    r.holdoutBefore = holdoutBefore_;
    // A fit that ended where it started (a start it could not improve) is drawn as it was: its
    // scores are the start's, without rendering every view again.
    const bool atStart = !scoredTheta_.empty() && readTheta(*fitter_) == scoredTheta_;
    if (trainBefore_) r.trainAfter = atStart ? *trainBefore_ : score(*fitter_, scene_.training);
    r.holdoutAfter = atStart ? holdoutBefore_ : scoreHoldout(*fitter_, scene_.holdout);
    r.holdoutSamplesPerPixel = scene_.holdout.supersampling() * scene_.holdout.supersampling();
    r.finite = allFinite(*fitter_);
    r.effects = fitter_->maps() ? fitter_->maps()->effects() : maps::MapEffects{};
    for (auto* group : fitter_->groups()) r.parameters.emplace_back(group->name(), group->count());
    r.tessLevel = fitter_->renderer().tessLevel();
    r.cageVertices = scene_.cage.vertexCount();
    r.cageFaces = scene_.cage.faceCount();
    r.cageCreases = int(scene_.cage.tags.creases.size());
    r.cageCorners = int(scene_.cage.tags.corners.size());
    r.patches = fitter_->renderer().patchCount();
    r.referenceTriangles = scene_.reference.faceCount();
    r.gl = context::currentGlInfo();
    r.glProvider = context.providerName();
    r.shaderVariants = programs_.variants();
    r.stopReason = toString(stopReason_);
    r.bestStep = schedule_.bestStep >= 0 ? schedule_.bestStep : bestStep_;

    // Outputs only now that everything has worked; each file appears whole or not at all.
    std::filesystem::create_directories(out);
    const mesh::PolygonMesh fittedWorld = this->fittedWorld();
    mesh::writeObj(out / "cage.obj", fittedWorld);
    FitOptions exportOptions = options_;
    exportOptions.out = out;
    const nlohmann::json exports =
        exportAsset(exportOptions, *fitter_, scene_.frame, fittedWorld, std::uint32_t(scene_.reference.faceCount()));
    for (const auto& [file, bytes] : exports.items()) r.exports[file] = bytes.get<std::uintmax_t>();
    const int res = options_.resolution;
    io::writeImage(out / "before.png", holdoutBefore_.firstView, res, res);
    io::writeImage(out / "after.png", r.holdoutAfter.firstView, res, res);
    io::writeImage(out / "target.png", scene_.holdout.readColor(0), res, res);
    r.seconds = secondsSince(started_);
    return r;
}

void FitRun::setTessLevel(int level) {
    FitOptions options = options_;
    options.tessLevel = level;
    validate(options);
    auto rebuilt =
        std::make_unique<CageFitter>(programs_, scene_.cage, fitSettings(options, scene_.cage, scene_.shading));
    rebuilt->restore(fitter_->state());
    // The rates and switches someone set by hand stay as they were.
    const auto before = fitter_->groups(), after = rebuilt->groups();
    for (size_t k = 0; k < before.size(); ++k) {
        rebuilt->setRates(*after[k], before[k]->settings().epsilon, before[k]->settings().learningRate);
        rebuilt->setOptimised(*after[k], fitter_->optimised(*before[k]));
    }
    fitter_ = std::move(rebuilt);
    options_ = options;
    scoredTheta_.clear();  // drawn at another level
    if (options_.schedule == Schedule::Plateau && schedule_.stageStart >= 0) applyStep();
}

}  // namespace subdfit::fit
