// `anascan capture` as an operator meets it: a device or scene that does not open fails
// before anything is written or asked; another stone is not mixed in without asking;
// a guided view that gave no model scan is not asked for again; a capture that only saves
// registers nothing again; Ctrl-C stops cleanly and says how to resume.
#include <nlohmann/json.hpp>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "cli_runner.hpp"
#include "text_match.hpp"

namespace anascan {
namespace {

namespace fs = std::filesystem;
using testing_util::contains;
using testing_util::occurrences;
using testing_util::run_cli;
using testing_util::run_shell;

class OperatorCapture : public testing_util::Cli {
protected:
    /// Quick simulated structured-light views, saved only.
    std::string capture(const std::string& scene, const std::string& extra) {
        return "capture --device sim:structured-light --scene " + scene + " --session " +
               session().string() + " --no-register --no-coverage " + extra + " </dev/null";
    }
    fs::path session() const { return dir_ / "stone"; }
    std::size_t scans() {
        const auto run =
            testing_util::run_cli_stdout("session info " + session().string() + " --json");
        const auto j = nlohmann::json::parse(run.output, nullptr, false);
        return j.is_object() ? j["scans"].size() : 0;
    }
};

TEST_F(OperatorCapture, UnknownSceneFailsOnceAndLeavesNoFolder) {
    const auto run = run_cli(capture("no-such-scene", "--views 2"));
    EXPECT_EQ(run.exit_code, 1) << run.output;
    EXPECT_EQ(occurrences(run.output, "unknown scene 'no-such-scene'"), 1u) << run.output;
    EXPECT_TRUE(contains(run.output, "small-block")) << "the known scenes: " << run.output;
    EXPECT_FALSE(contains(run.output, "0 scans")) << run.output;
    EXPECT_FALSE(fs::exists(session())) << "an empty session folder was left behind";
}

TEST_F(OperatorCapture, MissingCameraFailsBeforeThePrompt) {
    const std::string device = "v4l2:" + (dir_ / "video-none").string();
    const auto run = run_cli("capture --device " + device + " --session " + session().string() +
                             " --views 2 </dev/null");
    EXPECT_EQ(run.exit_code, 1) << run.output;
    EXPECT_FALSE(contains(run.output, "place the scanner")) << run.output;
    EXPECT_TRUE(contains(run.output, "video-none")) << run.output;
    EXPECT_FALSE(contains(run.output, "warning")) << run.output;
    EXPECT_FALSE(fs::exists(session()));
}

/// A registered capture of `scene` (empty: the device's default scene, named nowhere in the
/// URI: what a real scanner gives).
std::string registered_capture(const fs::path& session, const std::string& scene,
                               const std::string& extra) {
    const std::string device =
        scene.empty() ? "sim:structured-light" : "sim:structured-light --scene " + scene;
    return "capture --device " + device + " --session " + session.string() +
           " --no-coverage --flip-after 0 " + extra + " </dev/null";
}

std::size_t excluded_scans(const fs::path& session) {
    const auto run = testing_util::run_cli_stdout("session info " + session.string() + " --json");
    const auto j = nlohmann::json::parse(run.output, nullptr, false);
    std::size_t excluded = 0;
    if (j.is_object())
        for (const auto& scan : j["scans"]) excluded += scan.value("excluded", false) ? 1 : 0;
    return excluded;
}

// A model of two joined scans of the small block (the guided operator's first views). The
// same stone turned over joins nothing at first and is not asked about. The other stone
// comes through a URI with no scene name (the simulator's default scene, the octagon
// block): only the scans' geometry can tell. Without a terminal the capture refuses and
// the scan stays on disk, excluded; --mix-stones adds it.
TEST_F(OperatorCapture, AnotherStoneIsNotMixedInWithoutAskingTheSameTurnedOverIs) {
    ASSERT_NE(run_cli(registered_capture(session(), "small-block", "--views 6")).exit_code, 1);
    const fs::path turned_session = dir_ / "turned";
    fs::copy(session(), turned_session, fs::copy_options::recursive);
    const auto turned =
        run_cli(registered_capture(turned_session, "small-block-turned", "--views 7"));
    EXPECT_FALSE(contains(turned.output, "another stone?")) << turned.output;
    EXPECT_EQ(excluded_scans(turned_session), 0u) << turned.output;

    const auto other = run_cli(registered_capture(session(), "", "--views 8"));
    EXPECT_EQ(other.exit_code, 1) << other.output;
    EXPECT_TRUE(contains(other.output, "another stone?")) << other.output;
    EXPECT_TRUE(contains(other.output, "m across")) << "the figures: " << other.output;
    EXPECT_TRUE(contains(other.output, "--mix-stones")) << other.output;
    EXPECT_EQ(scans(), 7u) << "one scan to decide on, no more";
    EXPECT_EQ(excluded_scans(session()), 1u) << "the other stone's scan is out of the model";
    const auto mixed = run_cli(registered_capture(session(), "", "--views 8 --mix-stones"));
    EXPECT_FALSE(contains(mixed.output, "another stone?")) << "--mix-stones: nothing to ask";
    EXPECT_EQ(scans(), 8u);
    EXPECT_EQ(excluded_scans(session()), 1u) << "only the refused scan is out of the model";
}

// A capture that only saves adds to a registered session without registering its scans
// again (that rebuilds the live registrar, seconds per scan) and leaves their results alone.
TEST_F(OperatorCapture, ResumingWithoutRegistrationRegistersNothingAgain) {
    ASSERT_NE(run_cli(registered_capture(session(), "small-block", "--views 3")).exit_code, 1);
    const auto saved_only = run_cli(capture("small-block", "--views 4 --flip-after 0"));
    EXPECT_EQ(saved_only.exit_code, 0) << saved_only.output;
    EXPECT_TRUE(contains(saved_only.output, "saved scan 4")) << saved_only.output;
    EXPECT_FALSE(contains(saved_only.output, "registered again")) << saved_only.output;
    const auto info =
        testing_util::run_cli_stdout("session info " + session().string() + " --json");
    const auto j = nlohmann::json::parse(info.output, nullptr, false);
    ASSERT_TRUE(j.is_object()) << info.output;
    ASSERT_EQ(j["scans"].size(), 4u);
    for (int k = 0; k < 3; ++k) EXPECT_NE(j["scans"][k]["state"], "queued") << info.output;
    EXPECT_EQ(j["scans"][3]["state"], "queued") << "saved only, to register later";
}

/// The hints of a guided tour's output ("next: ..." lines), in order, and for each the scan
/// its view gave: the tour's first view is no hint, so hint k gives scan k + 2.
std::vector<std::string> hints(const std::string& output) {
    std::vector<std::string> out;
    std::istringstream lines(output);
    for (std::string line; std::getline(lines, line);) {
        const std::size_t at = line.find("; next: ");
        if (at != std::string::npos) out.push_back(line.substr(at + 8));
    }
    return out;
}

// The guided operator walks where the next-best-view says; a view whose scan did not join
// the model is named, and the next hint asks for another view.
TEST_F(OperatorCapture, AGuidedViewWhoseScanDidNotJoinIsNotAskedForAgain) {
    const auto run = run_cli(
        "--accept-poor capture --device sim:structured-light --scene "
        "small-block --session " +
        session().string() + " --tour guided --views 6 </dev/null");
    ASSERT_EQ(run.exit_code, 0) << run.output;
    const std::vector<std::string> asked = hints(run.output);
    ASSERT_GE(asked.size(), 2u) << run.output;
    const std::regex failed(
        R"(guided tour: scan (\d+), from the view asked for, is not in the model)");
    int failures = 0;
    for (std::sregex_iterator m(run.output.begin(), run.output.end(), failed), end; m != end; ++m) {
        const std::size_t scan = std::stoul((*m)[1]);
        const std::size_t k = scan - 2;       // The hint that gave it.
        if (k + 1 >= asked.size()) continue;  // The tour ended after it.
        ++failures;
        EXPECT_NE(asked[k + 1], asked[k]) << "scan " << scan << "'s view asked for again";
    }
    // On this block the guided views (1.4 m from the aim) often do not join: the test needs
    // one. If they all join one day, this fails and the test needs another scene.
    EXPECT_GT(failures, 0) << run.output;
}

TEST_F(OperatorCapture, CtrlCStopsAfterTheScanInFlightAndSaysHowToResume) {
    const fs::path log = dir_ / "log";
    // The simulated operator walks 30 s between views: SIGINT comes during the walk.
    const std::string command =
        "( " + std::string(ANASCAN_CLI) + " " +
        capture("small-block", "--views 5 --operator-pause-s 30") + " >" + log.string() +
        " 2>&1 & pid=$!; for i in $(seq 300); do " + "grep -q 'saved scan 1 ' " + log.string() +
        " && break; sleep 0.1; done; kill -INT $pid; wait $pid; echo " + "exit=$? )";
    const auto run = run_shell(command);
    std::string output;
    {
        std::FILE* f = std::fopen(log.c_str(), "r");
        ASSERT_NE(f, nullptr);
        for (int c; (c = std::fgetc(f)) != EOF;) output += static_cast<char>(c);
        std::fclose(f);
    }
    EXPECT_TRUE(contains(run.output, "exit=130")) << run.output << output;
    EXPECT_TRUE(contains(output, "stopped (Ctrl-C) after scan 1")) << output;
    EXPECT_TRUE(contains(output, "resume with: anascan capture --device sim:structured-light"))
        << output;
    EXPECT_EQ(scans(), 1u);
    const auto check = run_cli("session check " + session().string());
    EXPECT_EQ(check.exit_code, 0) << check.output;
}

}  // namespace
}  // namespace anascan
