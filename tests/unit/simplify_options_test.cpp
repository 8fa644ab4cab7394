// simplify's own options, made from their table (simplify/simplify_options.h): the command line
// reads each flag into its typed field and refuses a word it does not know; settingsJson records
// every option, "not given" as 0, as a batch asset's identity hashes it.
#include <gtest/gtest.h>

#include <algorithm>

#include "common/simplify_cli.h"
#include "util/error.h"

namespace subdfit::simplify {
namespace {

SimplifyOptions parsed(std::vector<std::string> args) {
    SimplifyOptions options;
    CLI::App app{"simplify"};
    apps::addSimplifySettings(app, options);
    std::reverse(args.begin(), args.end());  // CLI11 takes a vector last argument first
    app.parse(args);
    return options;
}

TEST(SimplifyOptionsCli, ReadsEachFlagIntoItsField) {
    const SimplifyOptions given =
        parsed({"--faces", "200", "--budget", "20KB", "--compare", "none", "--route", "cage", "--map-res", "6"});
    EXPECT_EQ(given.faces, 200);
    EXPECT_EQ(given.budget, 20000u);
    EXPECT_EQ(given.compare, CompareLevel::None);
    EXPECT_EQ(given.route, RouteChoice::Cage);
    EXPECT_EQ(given.fit.mapResolution, 6);

    const SimplifyOptions defaults = parsed({});
    EXPECT_FALSE(defaults.faces.has_value());
    EXPECT_FALSE(defaults.budget.has_value());
    EXPECT_EQ(defaults.compare, CompareLevel::Full);
    EXPECT_EQ(defaults.route, RouteChoice::Auto);
    EXPECT_EQ(defaults.fit.mapResolution, simplifyFitDefaults().mapResolution);
}

TEST(SimplifyOptionsCli, RefusesWhatNoRowTakes) {
    for (const std::vector<std::string>& args : std::vector<std::vector<std::string>>{
             {"--route", "triangles"}, {"--compare", "most"}, {"--faces", "3"}, {"--budget", "20parsecs"}}) {
        EXPECT_THROW(parsed(args), CLI::ParseError) << args[0] << " " << args[1];
    }
}

// --prefix is a part of a budget: given with one, under it.
TEST(SimplifyOptionsCli, APrefixIsPartOfABudget) {
    const auto checked = [](std::vector<std::string> args) {
        SimplifyOptions o = parsed(std::move(args));
        o.fit.reference = "reference.obj";
        o.fit.out = "out";
        validate(o);
        return o;
    };
    EXPECT_EQ(checked({"--budget", "100KB", "--prefix", "20KB"}).prefix, 20000u);
    for (const std::vector<std::string>& args : std::vector<std::vector<std::string>>{
             {"--prefix", "20KB"}, {"--budget", "20KB", "--prefix", "20KB"}, {"--budget", "5KB", "--prefix", "10KB"}}) {
        std::string joined;
        for (const std::string& a : args) joined += a + " ";
        EXPECT_THROW(checked(args), OptionError) << joined;
    }
}

TEST(SimplifySettings, RecordSimplifysOwnOptionsBesideTheFits) {
    SimplifyOptions options;
    nlohmann::json settings = settingsJson(options);
    EXPECT_EQ(settings["faces"], 0);
    EXPECT_EQ(settings["budget"], 0);
    EXPECT_EQ(settings["surface_samples"], 100000);
    EXPECT_EQ(settings["compare"], "full");
    EXPECT_EQ(settings["route"], "auto");
    EXPECT_EQ(settings["maps"], "displacement");

    options.faces = 200;
    options.budget = 20000;
    options.compare = CompareLevel::Fast;
    options.route = RouteChoice::Cage;
    settings = settingsJson(options);
    EXPECT_EQ(settings["faces"], 200);
    EXPECT_EQ(settings["budget"], 20000);
    EXPECT_EQ(settings["compare"], "fast");
    EXPECT_EQ(settings["route"], "cage");
}

}  // namespace
}  // namespace subdfit::simplify
