// What a checkpoint holds, and what a resume refuses.
//
// - The format number names what a checkpoint holds. Checkpoint::
//   layout_fingerprint() is the CRC-32 of the serialised empty state of a
//   run (every member of CheckpointState, the headers of flow.csv,
//   cells.csv and dm.csv): this test fails when it changes while
//   Checkpoint::format stays, so that a member or a column cannot be added
//   without a new format, which old checkpoints are then refused by. To
//   change what a checkpoint holds: raise Checkpoint::format
//   (include/rbc_ifem/ifem/checkpoint.h) and add the new pair below; never
//   edit a line. (The fingerprint is of a Boost binary archive, so of this
//   platform: x86-64 and Debian 12's Boost, as CI runs.)
// - A state written and read back is the same; a file whose layout line
//   names another layout is refused, and so is one whose header claims more
//   bytes than the file has, by the size check before anything is
//   allocated.

#include <rbc_ifem/base/input_error.h>
#include <rbc_ifem/ifem/checkpoint.h>

#include "check.h"

#include <deal.II/base/mpi.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <utility>
#include <vector>

using namespace rbc_ifem;

namespace
{
  /// Every format and its layout fingerprint, oldest first.
  const std::vector<std::pair<unsigned int, std::uint32_t>> formats =
    {{20261205, 1449497722}, {2026120502, 3940604644}, {2026120601, 321118345}};

  /// The message of the InputError that reading @p directory's checkpoint
  /// for @p run throws, or "" if it is read.
  std::string
  refusal(const std::string &directory, const ResumingRun &run)
  {
    try
      {
        Checkpoint(directory).read(run, MPI_COMM_WORLD);
      }
    catch (const InputError &e)
      {
        return e.what();
      }
    return "";
  }

  /// Replace the header line that starts with @p word in @p path.
  void
  rewrite_header(const std::string &path,
                 const std::string &word,
                 const std::string &value)
  {
    std::ifstream     in(path, std::ios::binary);
    std::stringstream text;
    text << in.rdbuf();
    std::string contents = text.str();
    const auto  start    = contents.find('\n' + word + ' ') + 1;
    const auto  end      = contents.find('\n', start);
    contents.replace(start, end - start, word + ' ' + value);
    std::ofstream(path, std::ios::binary) << contents;
  }
} // namespace

int
main(int argc, char *argv[])
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  Checker                          check;

  const std::uint32_t fingerprint = Checkpoint::layout_fingerprint();
  std::cout << "format " << Checkpoint::format << ", layout " << fingerprint
            << '\n';
  check.holds("the current format is the last of the table",
              formats.back().first == Checkpoint::format);
  check.holds("its layout is the one stored with it (if not: what a "
              "checkpoint holds changed; raise Checkpoint::format and add "
              "the new pair)",
              formats.back().second == fingerprint);
  for (unsigned int i = 1; i < formats.size(); ++i)
    check.holds("format " + std::to_string(formats[i].first) +
                  " is newer than the one before and holds another layout",
                formats[i].first > formats[i - 1].first &&
                  formats[i].second != formats[i - 1].second);

  const std::string directory = "checkpoint_format_test";
  std::filesystem::create_directory(directory);
  CheckpointState state;
  state.parameters  = "set Output directory = " + directory + "\n";
  state.record      = RunRecord(1, false);
  state.record.step = 3;
  state.record.cells.add(0.5, 0);
  state.fluid.n_dofs = 3;
  state.fluid_cells  = CellRecords(2);
  state.fluid_cells.add(CellId(4, {1, 7}), std::vector<double>{1., 2.});
  state.positions       = {Vector<double>(6)};
  state.positions[0](4) = 7.;
  const ResumingRun run{state.parameters, 3, 1, 6, 10};
  Checkpoint(directory).write(state, MPI_COMM_WORLD);
  const CheckpointState read = Checkpoint(directory).read(run, MPI_COMM_WORLD);
  check.holds("a state read back is the one written",
              read.record.step == 3 && read.fluid.n_dofs == 3 &&
                read.fluid_cells.size() == 1 &&
                read.fluid_cells.cell(0) == CellId(4, {1, 7}) &&
                read.fluid_cells.values(0)[1] == 2. &&
                read.positions[0](4) == 7.);

  const std::string path = Checkpoint(directory).path();
  rewrite_header(path, "layout", std::to_string(fingerprint + 1));
  const std::string other_layout = refusal(directory, run);
  std::cout << "another layout: " << other_layout << '\n';
  check.holds("a checkpoint of another layout is refused",
              other_layout.find("holds other tables or fields") !=
                std::string::npos);

  Checkpoint(directory).write(state, MPI_COMM_WORLD);
  rewrite_header(path, "bytes", "9184072000");
  const std::string too_long = refusal(directory, run);
  std::cout << "a header of 9,184,072,000 bytes: " << too_long << '\n';
  check.holds("a header claiming more bytes than the file has is refused "
              "as truncated",
              too_long.find("truncated") != std::string::npos);
  rewrite_header(path, "bytes", "-5");
  const std::string negative = refusal(directory, run);
  check.holds("a header with a negative byte count is refused as damaged",
              negative.find("checkpoint.bin: its header is damaged") !=
                std::string::npos);

  std::filesystem::remove_all(directory);
  std::filesystem::create_directory(directory);
  Checkpoint(directory).write(state, MPI_COMM_WORLD);
  state.record.step = 4;
  Checkpoint(directory).write(state, MPI_COMM_WORLD);
  rewrite_header(path, "crc32", "1");
  Checkpoint            fallback(directory);
  const CheckpointState earlier = fallback.read(run, MPI_COMM_WORLD);
  std::cout << "checkpoint.bin damaged: resumed from "
            << fallback.resumed_from() << ", step " << earlier.record.step
            << '\n';
  check.holds("a damaged checkpoint.bin gives way to the one before, "
              "checkpoint_previous.bin, and the resume says so",
              earlier.record.step == 3 &&
                fallback.resumed_from().find(
                  "checkpoint_previous.bin (checkpoint.bin: it is damaged") ==
                  0);
  std::filesystem::remove_all(directory);
  return check.exit_code();
}
