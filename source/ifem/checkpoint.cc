#include <rbc_ifem/base/input_error.h>
#include <rbc_ifem/base/output.h>
#include <rbc_ifem/base/output_error.h>
#include <rbc_ifem/base/parameter_text.h>
#include <rbc_ifem/diffusion/uptake.h>
#include <rbc_ifem/ifem/checkpoint.h>

#include <deal.II/base/mpi.h>

#include <boost/archive/binary_iarchive.hpp>
#include <boost/archive/binary_oarchive.hpp>
#include <boost/crc.hpp>
#include <boost/serialization/array.hpp>
#include <boost/serialization/string.hpp>
#include <boost/serialization/utility.hpp>
#include <boost/serialization/vector.hpp>

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace rbc_ifem
{
  namespace
  {
    const std::string title = "rbc-ifem checkpoint";

    std::uint32_t
    crc32(const std::string &bytes)
    {
      boost::crc_32_type crc;
      crc.process_bytes(bytes.data(), bytes.size());
      return crc.checksum();
    }

    /// @p state as a boost binary archive.
    std::string
    serialized(const CheckpointState &state)
    {
      std::ostringstream bytes;
      {
        boost::archive::binary_oarchive archive(bytes);
        archive << state;
      }
      return bytes.str();
    }

    /// The parameters a resumed run may change: how long it runs and what
    /// it reports, not what it computes.
    bool
    may_change_on_resume(const std::string &name)
    {
      return name == "Output directory" || name == "Time/Number of steps" ||
             name == "Time/Output interval" ||
             name == "Immersed cells/Resume" ||
             name == "Immersed cells/Checkpoint interval" ||
             name == "Immersed cells/Progress interval";
    }

    /// The header line "@p word VALUE" of @p in, or a damaged header.
    template <typename Value>
    Value
    header_value(std::istream &in, const std::string &word)
    {
      // A number read as text first: ">>" would read "-5" into an unsigned
      // Value as a huge one.
      std::string found, text;
      in >> found >> text;
      Value              value{};
      std::istringstream number(text);
      number >> value;
      if (!in || found != word || text.empty() || text[0] == '-' || !number ||
          !number.eof())
        throw std::runtime_error("its header is damaged");
      return value;
    }

    /// The @p n_blocks lines "block SIZE CRC" of a header, in a file of
    /// @p file_size bytes.
    std::vector<std::pair<std::uint64_t, std::uint32_t>>
    block_lines(std::istream       &in,
                const std::uint64_t n_blocks,
                const std::uint64_t file_size)
    {
      // Each line is at least 10 characters: a count beyond the file's size
      // is damage, not a reason to allocate.
      if (n_blocks > file_size / 10)
        throw std::runtime_error("its header is damaged");
      std::vector<std::pair<std::uint64_t, std::uint32_t>> blocks;
      for (std::uint64_t b = 0; b < n_blocks; ++b)
        {
          const auto    size = header_value<std::uint64_t>(in, "block");
          std::uint32_t crc  = 0;
          if (!(in >> crc))
            throw std::runtime_error("its header is damaged");
          blocks.emplace_back(size, crc);
        }
      return blocks;
    }
  } // namespace

  std::uint32_t
  Checkpoint::layout_fingerprint()
  {
    CheckpointState probe;
    probe.record = RunRecord(2, true);
    return crc32(serialized(probe));
  }

  Checkpoint::Checkpoint(const std::string &directory)
    : directory(directory)
    , source("checkpoint.bin")
  {}

  std::vector<std::string>
  Checkpoint::find_in(const std::string &directory)
  {
    namespace fs = std::filesystem;
    std::vector<std::string> found;
    const auto               add_from = [&found](const fs::path &folder) {
      for (const char *name : {"checkpoint.bin", "checkpoint_previous.bin"})
        if (fs::exists(folder / name))
          found.push_back((folder / name).string());
    };
    std::error_code error;
    if (!fs::is_directory(directory, error))
      return found;
    add_from(directory);
    for (const fs::directory_entry &entry :
         fs::directory_iterator(directory, error))
      if (entry.is_directory(error))
        add_from(entry.path());
    std::sort(found.begin(), found.end());
    return found;
  }

  std::string
  Checkpoint::path() const
  {
    return directory + "/checkpoint.bin";
  }

  bool
  Checkpoint::exists() const
  {
    return std::filesystem::exists(path()) ||
           std::filesystem::exists(previous_path());
  }

  std::string
  Checkpoint::previous_path() const
  {
    return directory + "/checkpoint_previous.bin";
  }

  void
  Checkpoint::write(const CheckpointState &state,
                    const MPI_Comm         communicator) const
  {
    const std::string block = state.fluid_cells.to_bytes();
    const std::vector<std::pair<std::uint64_t, std::uint32_t>> blocks =
      Utilities::MPI::gather(
        communicator,
        std::make_pair(static_cast<std::uint64_t>(block.size()), crc32(block)));
    const bool  first = Utilities::MPI::this_mpi_process(communicator) == 0;
    std::string head;
    if (first)
      {
        const std::string shared = serialized(state);
        std::uint64_t     bytes  = shared.size();
        for (const auto &[size, crc] : blocks)
          bytes += size;
        std::ostringstream header;
        header << title << "\nformat " << format << "\nlayout "
               << layout_fingerprint() << "\nbytes " << bytes << "\ncrc32 "
               << crc32(shared) << "\nshared " << shared.size() << "\nblocks "
               << blocks.size() << '\n';
        for (const auto &[size, crc] : blocks)
          header << "block " << size << ' ' << crc << '\n';
        head = header.str() + shared;
      }
    // The new one is complete on the disk before any name changes, and each
    // rename replaces a name in one step: a run killed at any moment leaves
    // checkpoint.bin, the last complete checkpoint or the new one.
    const std::string fresh = path() + ".part";
    write_in_rank_order(fresh, head, block, communicator);
    if (!first)
      return;
    if (rotate && std::filesystem::exists(path()))
      keep_as_previous();
    rename_written_file(fresh, path());
    sync_directory();
  }

  void
  Checkpoint::keep_as_previous() const
  {
    // A second name for checkpoint.bin, then the rename that replaces the
    // older checkpoint_previous.bin with it; a copy where links are not
    // allowed.
    const std::string kept = previous_path() + ".part";
    ::unlink(kept.c_str());
    if (::link(path().c_str(), kept.c_str()) != 0)
      {
        std::ifstream      in(path(), std::ios::binary);
        std::ostringstream bytes;
        bytes << in.rdbuf();
        write_synced_file(kept, bytes.str());
      }
    rename_written_file(kept, previous_path());
  }

  void
  Checkpoint::sync_directory() const
  {
    // The renames are on the disk only once the directory is.
    const int handle = ::open(directory.c_str(), O_RDONLY | O_DIRECTORY);
    if (handle < 0)
      return;
    const int synced = ::fsync(handle);
    const int error  = errno;
    ::close(handle);
    if (synced != 0 && error != EINVAL)
      throw OutputError(directory, std::strerror(error));
  }

  struct Checkpoint::Contents
  {
    std::string shared; ///< the shared part, checked
    /// The size and CRC-32 of each fluid block, which start at first_block.
    std::vector<std::pair<std::uint64_t, std::uint32_t>> blocks;
    std::uint64_t                                        first_block = 0;
  };

  Checkpoint::Contents
  Checkpoint::contents(const std::string &file) const
  {
    std::ifstream in(file, std::ios::binary);
    if (!in)
      throw std::runtime_error("it does not exist or cannot be read");
    std::string first_line;
    std::getline(in, first_line);
    if (first_line != title)
      throw std::runtime_error("it is not an rbc-ifem checkpoint");
    const auto file_format = header_value<unsigned long>(in, "format");
    if (file_format != format)
      throw std::runtime_error(
        "it has the format " + std::to_string(file_format) +
        "; this version of rbc-ifem reads " + std::to_string(format));
    const auto layout = header_value<std::uint32_t>(in, "layout");
    if (layout != layout_fingerprint())
      throw std::runtime_error(
        "it holds other tables or fields than this version of rbc-ifem "
        "writes (layout " +
        std::to_string(layout) + ", this version's " +
        std::to_string(layout_fingerprint()) +
        "): it comes from another version with the same format number");
    const auto bytes    = header_value<std::uint64_t>(in, "bytes");
    const auto crc      = header_value<std::uint32_t>(in, "crc32");
    const auto shared   = header_value<std::uint64_t>(in, "shared");
    const auto n_blocks = header_value<std::uint64_t>(in, "blocks");
    Contents   found;
    found.blocks = block_lines(in, n_blocks, std::filesystem::file_size(file));
    std::uint64_t sum = shared;
    for (const auto &[size, block_crc] : found.blocks)
      sum += size;
    in.get();
    // The size the header claims is checked against the file's before
    // anything is allocated for it.
    const std::uint64_t start     = in.tellg();
    const std::uint64_t available = std::filesystem::file_size(file) - start;
    if (bytes > available)
      throw std::runtime_error("it is truncated: " + std::to_string(available) +
                               " of its " + std::to_string(bytes) +
                               " bytes are there");
    if (sum != bytes)
      throw std::runtime_error("its header is damaged");
    found.shared.assign(shared, '\0');
    in.read(found.shared.data(), shared);
    if (crc32(found.shared) != crc)
      throw std::runtime_error(
        "it is damaged: the checksum of its contents does not match");
    found.first_block = start + shared;
    return found;
  }

  CheckpointState
  Checkpoint::read_file(const std::string &file,
                        const MPI_Comm     communicator) const
  {
    const Contents                  found = contents(file);
    CheckpointState                 state;
    std::istringstream              bytes(found.shared);
    boost::archive::binary_iarchive archive(bytes);
    archive >> state;
    const unsigned int n_ranks = Utilities::MPI::n_mpi_processes(communicator);
    std::ifstream      in(file, std::ios::binary);
    std::uint64_t      at = found.first_block;
    for (unsigned int b = 0; b < found.blocks.size(); ++b)
      {
        const auto [size, crc] = found.blocks[b];
        if (b % n_ranks == Utilities::MPI::this_mpi_process(communicator))
          {
            std::string block(size, '\0');
            in.seekg(at);
            in.read(block.data(), size);
            if (crc32(block) != crc)
              throw std::runtime_error(
                "it is damaged: the checksum of its contents does not match");
            const CellRecords records = CellRecords::from_bytes(block);
            if (state.fluid_cells.size() == 0)
              state.fluid_cells = CellRecords(records.values_per_cell());
            for (unsigned int r = 0; r < records.size(); ++r)
              state.fluid_cells.add(records.cell(r), records.values(r));
          }
        at += size;
      }
    return state;
  }

  std::optional<CheckpointState>
  Checkpoint::load(const std::string &file,
                   std::string       &why_not,
                   const MPI_Comm     communicator) const
  {
    std::optional<CheckpointState> state;
    try
      {
        state = read_file(file, communicator);
      }
    catch (const std::exception &e)
      {
        why_not = e.what();
      }
    // A block only one rank read can be damaged: the first reason, if any
    // rank has one, is every rank's.
    for (const std::string &reason :
         Utilities::MPI::all_gather(communicator, why_not))
      if (!reason.empty())
        {
          why_not = reason;
          return {};
        }
    return state;
  }

  CheckpointState
  Checkpoint::read(const ResumingRun &run, const MPI_Comm communicator)
  {
    std::string                    why_not;
    std::optional<CheckpointState> state = load(path(), why_not, communicator);
    if (!state)
      {
        std::string why_not_previous;
        state = load(previous_path(), why_not_previous, communicator);
        if (!state)
          throw InputError(
            "Immersed cells/Resume",
            "true",
            "it needs a checkpoint of an earlier run in " + directory +
              ", and none can be used: checkpoint.bin: " + why_not +
              "; checkpoint_previous.bin: " + why_not_previous + ".");
        // checkpoint.bin is no state to keep: the next checkpoint replaces
        // it, and checkpoint_previous.bin stays until then.
        rotate = false;
        source = "checkpoint_previous.bin (checkpoint.bin: " + why_not + ")";
      }
    check_parameters(state->parameters, run);
    check_sizes(*state, run);
    return *state;
  }

  const std::string &
  Checkpoint::resumed_from() const
  {
    return source;
  }

  void
  Checkpoint::check_parameters(const std::string &written,
                               const ResumingRun &run) const
  {
    const auto before = parameter_values(written);
    for (const auto &[name, value] : parameter_values(run.parameters))
      {
        const auto old = before.find(name);
        if (old != before.end() && old->second != value &&
            !may_change_on_resume(name))
          throw InputError(
            name,
            value,
            "the checkpoint " + path() + " was written by a run with " + name +
              " = " + old->second +
              ". A resumed run computes what the run that "
              "wrote it did: only Time/Number of steps, "
              "Time/Output interval, Immersed cells/Resume, "
              "Checkpoint interval and Progress interval may "
              "change (and Output directory, for a copied run).");
      }
  }

  void
  Checkpoint::check_sizes(const CheckpointState &state,
                          const ResumingRun     &run) const
  {
    if (state.fluid.n_dofs != run.n_fluid_dofs ||
        state.positions.size() != run.n_cells ||
        state.positions[0].size() != run.n_point_values)
      throw InputError("Immersed cells/Resume",
                       "true",
                       "the checkpoint " + path() + " comes from a run with " +
                         std::to_string(state.fluid.n_dofs) +
                         " fluid DoFs and " +
                         std::to_string(state.positions.size()) +
                         " cell(s); this run has " +
                         std::to_string(run.n_fluid_dofs) + " and " +
                         std::to_string(run.n_cells) +
                         ": it was written for another mesh or layout.");
    if (state.record.step > run.n_steps)
      throw InputError("Time/Number of steps",
                       std::to_string(run.n_steps),
                       "a resumed run must go to the checkpoint's step " +
                         std::to_string(state.record.step) + " or beyond.");
  }
} // namespace rbc_ifem
