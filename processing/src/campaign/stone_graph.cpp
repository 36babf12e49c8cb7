// The campaign's match graph: the verified pairs under the per-scan RMS gate and the loop
// checks (triangles, then cycles against the poses of better pairs), and the
// stones as the connected components of what is left.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <numeric>
#include <optional>
#include <string>

#include "anascan/processing/campaign/campaign_stages.hpp"
#include "registration/batch/steps.hpp"  // DisjointSets

namespace anascan {
namespace {

struct Edge {
    std::size_t s = 0, t = 0;
    Pose T_t_s = Pose::Identity();
    double ratio = 0.0;  ///< RMS over the target spacing.
    bool on = true;
};

struct Graph {
    const std::vector<PreparedSummary>& scans;
    const StoneGraphConfig& config;
    std::vector<Edge> edges;
    StoneGraph& out;
};

/// The pose mapping `from` into `to` along edge e.
Pose edge_pose(const Edge& e, std::size_t from) {
    return from == e.s ? e.T_t_s : e.T_t_s.inverse();
}

struct LoopError {
    double rotation_deg = 0.0, offset_m = 0.0;
};

/// E maps scan x into itself around a loop: its rotation and the move of x's centre.
LoopError loop_error(const Pose& E, const Eigen::Vector3d& centre_m) {
    return {Eigen::AngleAxisd(E.linear()).angle() * 180.0 / M_PI, (E * centre_m - centre_m).norm()};
}

bool closes(const Graph& g, const LoopError& e, std::initializer_list<std::size_t> scans) {
    double spacing_m = 0.0;
    for (std::size_t x : scans) spacing_m = std::max(spacing_m, g.scans[x].spacing_m);
    return e.rotation_deg <= g.config.max_loop_rotation_deg &&
           e.offset_m <= g.config.max_loop_spacing_factor * spacing_m;
}

std::string loop_text(const LoopError& e) {
    char text[96];
    std::snprintf(text, sizeof text, "%.2f° and %.2f mm", e.rotation_deg, 1e3 * e.offset_m);
    return text;
}

void warn(Graph& g, std::size_t scan, const std::string& text) {
    std::string& w = g.out.warning_of_scan[scan];
    if (w.empty()) w = text;
}

/// The pair most above the per-scan gate: its ratio over the better of its scans' best
/// ratios among the pairs still on, when above the factor.
std::optional<std::size_t> worst_above_gate(const Graph& g) {
    std::vector<double> best(g.scans.size(), std::numeric_limits<double>::infinity());
    for (const Edge& e : g.edges) {
        if (!e.on) continue;
        best[e.s] = std::min(best[e.s], e.ratio);
        best[e.t] = std::min(best[e.t], e.ratio);
    }
    std::optional<std::size_t> worst;
    double worst_excess = g.config.relative_rms_gate_factor;
    for (std::size_t i = 0; i < g.edges.size(); ++i) {
        const Edge& e = g.edges[i];
        const double excess = e.ratio / std::min(best[e.s], best[e.t]);
        if (e.on && excess > worst_excess) {
            worst = i;
            worst_excess = excess;
        }
    }
    return worst;
}

/// Cuts the pair most above the per-scan gate, then judges the rest again (a look-alike that
/// was its scan's best pair no longer sets that scan's gate), until none is above.
void relative_gate(Graph& g) {
    while (const std::optional<std::size_t> worst = worst_above_gate(g)) {
        g.edges[*worst].on = false;
        ++g.out.relative_gated_pairs;
    }
}

struct Triangle {
    std::array<std::size_t, 3> edge{};  ///< Indices into Graph::edges: a-b, b-c, a-c.
    std::array<std::size_t, 3> scan{};  ///< a < b < c.
};

std::vector<Triangle> triangles(const Graph& g) {
    std::map<std::pair<std::size_t, std::size_t>, std::size_t> index;
    std::vector<std::vector<std::size_t>> near(g.scans.size());
    for (std::size_t i = 0; i < g.edges.size(); ++i) {
        const Edge& e = g.edges[i];
        if (!e.on) continue;
        index[{std::min(e.s, e.t), std::max(e.s, e.t)}] = i;
        near[std::min(e.s, e.t)].push_back(std::max(e.s, e.t));
    }
    std::vector<Triangle> out;
    for (const auto& [ab, e_ab] : index) {
        for (std::size_t c : near[ab.second]) {
            const auto ac = index.find({ab.first, c});
            if (ac != index.end())
                out.push_back(
                    {{e_ab, index.at({ab.second, c}), ac->second}, {ab.first, ab.second, c}});
        }
    }
    return out;
}

/// One round: every triangle that does not close cuts its worst pair among those that
/// close no triangle (or its worst when all do). Returns whether it cut any.
bool triangle_round(Graph& g) {
    const std::vector<Triangle> all = triangles(g);
    std::vector<bool> confirmed(g.edges.size(), false);
    std::vector<std::pair<Triangle, LoopError>> open;
    for (const Triangle& tri : all) {
        const auto [a, b, c] = tri.scan;
        const Pose E = edge_pose(g.edges[tri.edge[2]], c) * edge_pose(g.edges[tri.edge[1]], b) *
                       edge_pose(g.edges[tri.edge[0]], a);  // a → b → c → a.
        const LoopError error = loop_error(E, g.scans[a].centre_m);
        if (closes(g, error, {a, b, c})) {
            for (std::size_t e : tri.edge) confirmed[e] = true;
        } else {
            open.emplace_back(tri, error);
        }
    }
    bool cut = false;
    for (const auto& [tri, error] : open) {
        const auto is_on = [&](std::size_t e) { return g.edges[e].on; };
        if (!std::all_of(tri.edge.begin(), tri.edge.end(), is_on)) continue;  // Cut this round.
        std::optional<std::size_t> worst;
        for (bool any : {false, true}) {
            for (std::size_t e : tri.edge) {
                if (confirmed[e] && !any) continue;
                if (!worst || g.edges[e].ratio > g.edges[*worst].ratio) worst = e;
            }
            if (worst) break;
        }
        g.edges[*worst].on = false;
        ++g.out.triangle_cut_pairs;
        cut = true;
        const std::string text = "a triangle of its pairs did not close (" + loop_text(error) +
                                 "); the worst of its pairs was cut";
        for (std::size_t x : tri.scan) warn(g, x, text);
    }
    return cut;
}

/// Joins the pairs best first; a pair inside one stone must agree with its poses.
detail::DisjointSets cycle_check(Graph& g) {
    std::vector<std::size_t> order(g.edges.size());
    std::iota(order.begin(), order.end(), std::size_t{0});
    std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
        return g.edges[a].ratio < g.edges[b].ratio;
    });
    detail::DisjointSets sets(g.scans.size());
    std::vector<Pose> T_root(g.scans.size(), Pose::Identity());
    std::vector<std::vector<std::size_t>> members(g.scans.size());
    for (std::size_t i = 0; i < g.scans.size(); ++i) members[i] = {i};
    for (std::size_t i : order) {
        Edge& e = g.edges[i];
        if (!e.on) continue;
        const std::size_t rs = sets.find(e.s), rt = sets.find(e.t);
        if (rs == rt) {
            const Pose E = (T_root[e.t].inverse() * T_root[e.s]).inverse() * e.T_t_s;
            const LoopError error = loop_error(E, g.scans[e.s].centre_m);
            if (closes(g, error, {e.s, e.t})) continue;
            e.on = false;
            ++g.out.cycle_cut_pairs;
            const std::string text =
                "one of its pairs disagrees with the poses of its stone's better "
                "pairs (" +
                loop_text(error) + "): its placement is ambiguous";
            warn(g, e.s, text);
            warn(g, e.t, text);
            continue;
        }
        // Move t's stone into s's: T_rs_m = T_rs_s · T_s_t · T_rt_t⁻¹ · T_rt_m.
        const Pose T_rs_rt = T_root[e.s] * e.T_t_s.inverse() * T_root[e.t].inverse();
        for (std::size_t m : members[rt]) T_root[m] = T_rs_rt * T_root[m];
        sets.unite(rs, rt);
        const std::size_t root = sets.find(rs), other = root == rs ? rt : rs;
        members[root].insert(members[root].end(), members[other].begin(), members[other].end());
        members[other].clear();
        if (root != rs) {  // Poses are relative to s's old root; re-root onto the new one.
            const Pose T_new_old = T_root[root].inverse();
            for (std::size_t m : members[root]) T_root[m] = T_new_old * T_root[m];
        }
    }
    return sets;
}

/// Bridge finding (Tarjan) over the pairs still on: marks every scan with a pair that lies
/// on a loop (a pair whose removal leaves its scans joined).
struct LoopFinder {
    const Graph& g;
    std::vector<std::vector<std::pair<std::size_t, std::size_t>>> near;  ///< (scan, edge).
    std::vector<int> order, low;
    std::vector<bool> on_loop;
    int time = 0;

    explicit LoopFinder(const Graph& graph)
        : g(graph),
          near(graph.scans.size()),
          order(graph.scans.size(), -1),
          low(graph.scans.size(), 0),
          on_loop(graph.scans.size(), false) {
        for (std::size_t i = 0; i < g.edges.size(); ++i) {
            if (!g.edges[i].on) continue;
            near[g.edges[i].s].emplace_back(g.edges[i].t, i);
            near[g.edges[i].t].emplace_back(g.edges[i].s, i);
        }
        for (std::size_t x = 0; x < near.size(); ++x)
            if (order[x] < 0) visit(x, g.edges.size());
    }

    void visit(std::size_t x, std::size_t via_edge) {
        order[x] = low[x] = time++;
        for (const auto& [y, e] : near[x]) {
            if (e == via_edge) continue;
            if (order[y] < 0) {
                visit(y, e);
                low[x] = std::min(low[x], low[y]);
                if (low[y] <= order[x]) on_loop[x] = on_loop[y] = true;  // Not a bridge.
            } else {
                low[x] = std::min(low[x], order[y]);
                on_loop[x] = on_loop[y] = true;  // A back edge closes a loop.
            }
        }
    }
};

/// Scans that no closed loop of pairs confirms are placed by one chain of pairs only.
void warn_unconfirmed(Graph& g) {
    const LoopFinder loops(g);
    for (std::size_t x = 0; x < g.scans.size(); ++x) {
        if (!loops.on_loop[x])
            warn(g, x, "no loop of pairs confirms its placement (one chain of pairs only)");
    }
}

void components(Graph& g, detail::DisjointSets& sets) {
    const std::size_t n = g.scans.size();
    std::vector<std::vector<std::size_t>> members(n);
    for (std::size_t i = 0; i < n; ++i) members[sets.find(i)].push_back(i);
    for (std::vector<std::size_t>& m : members) {
        if (m.size() >= 2) g.out.stones.push_back(std::move(m));
    }
    std::stable_sort(g.out.stones.begin(), g.out.stones.end(),
                     [](const auto& a, const auto& b) { return a.size() > b.size(); });
    g.out.stone_of_scan.assign(n, -1);
    for (std::size_t s = 0; s < g.out.stones.size(); ++s) {
        for (std::size_t i : g.out.stones[s]) g.out.stone_of_scan[i] = static_cast<int>(s);
    }
    for (std::size_t i = 0; i < n; ++i) {
        if (g.out.stone_of_scan[i] < 0) g.out.warning_of_scan[i].clear();
    }
}

}  // namespace

StoneGraph find_stones(const std::vector<PreparedSummary>& scans,
                       const std::vector<RegisteredPair>& pairs, const CampaignConfig& config) {
    StoneGraph out;
    out.warning_of_scan.assign(scans.size(), {});
    Graph g{scans, config.graph, {}, out};
    for (const RegisteredPair& p : pairs) {
        if (!p.result.verified) continue;
        const double spacing_m = p.result.target_spacing_m > 0.0 ? p.result.target_spacing_m : 1.0;
        g.edges.push_back(
            {p.source, p.target, p.result.T_target_source, p.result.rms_m / spacing_m});
    }
    relative_gate(g);
    while (triangle_round(g)) {
    }
    detail::DisjointSets sets = cycle_check(g);
    warn_unconfirmed(g);
    components(g, sets);
    return out;
}

}  // namespace anascan
