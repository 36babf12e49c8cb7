// anascan blocks assemble DIR --pair A:2=B:5 [--pair ...] [--coplanar A:1=B:3]
//   [--colinear A:1/4=B:3/0] [--fixed A] --out ASSEMBLY/   (or --proposals P.json --accepted)
// The penetration-free alignment of neighbouring blocks (method paper §5.3): DIR holds the
// ID.features.json of `blocks features`, whose models are read again; ASSEMBLY/ receives
// assembly.conf (one bmesh line per block), assembly.json (the report) and assembly.ply
// (the blocks coloured, matching faces by their gap, penetrating points red).
#include "anascan/acquisition/blocks/block_alignment.hpp"
#include "anascan/acquisition/blocks/block_proposals.hpp"
#include "assembly_report.hpp"
#include "commands.hpp"

namespace anascan::cli {
namespace {

namespace ra = anascan::reassembly;
namespace acq = anascan::acquisition;

struct AssembleBlocksOptions {
    std::string dir, out, proposals;
    std::vector<std::string> pairs, coplanar, colinear, fixed;
    bool accepted = false;
    int max_iterations = 60;
    std::string joint_normal = "plane";
};

template <typename T>
T or_fail(Expected<T> x) {
    if (!x) fail_command(x.error());
    return std::move(*x);
}

// The expert's links: given on the command line, or the accepted pairs of a proposals file.
acq::AssemblyLinks links_of(const AssembleBlocksOptions& o) {
    if (!o.proposals.empty() && !o.accepted)
        fail_command({ErrorCode::kInvalidArgument,
                      "--proposals needs --accepted (only accepted pairs are assembled)"});
    acq::AssemblyLinks links{
        .contacts = o.pairs, .coplanar = o.coplanar, .colinear = o.colinear, .fixed = o.fixed};
    if (o.proposals.empty()) return links;
    links.contacts = acq::accepted_pairs(or_fail(acq::read_block_proposals(o.proposals)));
    if (links.contacts.empty())
        fail_command(
            {ErrorCode::kInvalidArgument, o.proposals + ": no accepted pair (blocks accept)"});
    return links;
}

void run_assemble_blocks(const AssembleBlocksOptions& o) {
    const acq::BlockFolder folder = or_fail(acq::open_block_folder(o.dir));
    ra::AssemblyProblem p = or_fail(acq::parse_assembly_links(folder, links_of(o)));
    p.blocks = or_fail(acq::load_folder_blocks(folder));
    const ra::AssemblyConfig config{.max_iterations = o.max_iterations,
                                    .joint_normal = o.joint_normal == "plane"
                                                        ? ra::JointNormal::kFacePlane
                                                        : ra::JointNormal::kVertex};
    const acq::BlockAlignment a = or_fail(acq::align_blocks(p, config));
    if (auto ok = acq::write_assembly_folder(o.out, folder, p, a); !ok) fail_command(ok.error());
    print_assembly_report(p, a.result, a.check);
    const ra::AssemblyResult& r = a.result;
    if (r.status != ra::AssemblyStatus::kOk)
        throw CommandFailed(std::string(ra::to_string(r.status)) + ": " + r.message +
                            (r.offending.empty() ? "" : ": ") + [&] {
                                std::string s;
                                for (const auto& x : r.offending) s += (s.empty() ? "" : ", ") + x;
                                return s;
                            }());
}

}  // namespace

void add_blocks_assemble_command(CLI::App& blocks) {
    auto o = std::make_shared<AssembleBlocksOptions>();
    auto* cmd = blocks.add_subcommand(
        "assemble",
        "Penetration-free alignment of neighbouring blocks (faces touching, co-planar, co-linear)");
    cmd->add_option("dir", o->dir, "Folder of blocks features (ID.features.json)")->required();
    cmd->add_option("--pair", o->pairs,
                    "Matching faces that touch, A:F=B:G (face ids of blocks features)");
    cmd->add_option("--coplanar", o->coplanar, "Faces that should be co-planar, A:F=B:G");
    cmd->add_option("--colinear", o->colinear,
                    "Edges that should be co-linear, A:F/G=B:H/K (edge of faces F, G)");
    cmd->add_option("--fixed", o->fixed, "Blocks that stay in place (default: the first)");
    cmd->add_option("--proposals", o->proposals, "proposals.json of blocks match")
        ->check(CLI::ExistingFile);
    cmd->add_flag("--accepted", o->accepted, "Assemble the pairs accepted in --proposals");
    cmd->add_option("--max-iterations", o->max_iterations, "Iterations at most")
        ->check(CLI::PositiveNumber);
    cmd->add_option("--joint-normal", o->joint_normal,
                    "Contact rows along the partner's face plane (plane, default) or its vertex "
                    "normals (vertex, the paper's)")
        ->check(CLI::IsMember({"vertex", "plane"}));
    cmd->add_option("--out", o->out, "Output folder (assembly.conf, assembly.json, assembly.ply)")
        ->required();
    cmd->callback([o] {
        if (o->pairs.empty() && o->proposals.empty())
            fail_command({ErrorCode::kInvalidArgument,
                          "give --pair A:F=B:G or --proposals FILE --accepted"});
        run_assemble_blocks(*o);
    });
}

}  // namespace anascan::cli
