#include <rbc_ifem/base/input_error.h>
#include <rbc_ifem/base/output.h>
#include <rbc_ifem/base/parameter_text.h>
#include <rbc_ifem/diffusion/uptake.h>
#include <rbc_ifem/ifem/checkpoint.h>

#include <boost/archive/binary_iarchive.hpp>
#include <boost/archive/binary_oarchive.hpp>
#include <boost/crc.hpp>
#include <boost/serialization/array.hpp>
#include <boost/serialization/string.hpp>
#include <boost/serialization/utility.hpp>
#include <boost/serialization/vector.hpp>

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
      std::string found;
      Value       value{};
      in >> found >> value;
      if (!in || found != word)
        throw std::runtime_error("its header is damaged");
      return value;
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
  {}

  std::string
  Checkpoint::path() const
  {
    return directory + "/checkpoint.bin";
  }

  void
  Checkpoint::write(const CheckpointState &state,
                    const MPI_Comm         communicator) const
  {
    if (Utilities::MPI::this_mpi_process(communicator) != 0)
      return;
    const std::string payload = serialized(state);
    // The last two: the one before stays as checkpoint_previous.bin.
    if (std::filesystem::exists(path()))
      std::filesystem::rename(path(), directory + "/checkpoint_previous.bin");
    write_file_atomically(path(), [&](std::ostream &out) {
      out << title << "\nformat " << format << "\nlayout "
          << layout_fingerprint() << "\nbytes " << payload.size() << "\ncrc32 "
          << crc32(payload) << '\n'
          << payload;
    });
  }

  std::string
  Checkpoint::payload() const
  {
    std::ifstream in(path(), std::ios::binary);
    std::string   first_line;
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
    const auto bytes = header_value<unsigned long>(in, "bytes");
    const auto crc   = header_value<std::uint32_t>(in, "crc32");
    in.get();
    // The size the header claims is checked against the file's before
    // anything is allocated for it.
    const auto start     = in.tellg();
    const auto available = std::filesystem::file_size(path()) - start;
    if (bytes > available)
      throw std::runtime_error("it is truncated: " + std::to_string(available) +
                               " of its " + std::to_string(bytes) +
                               " bytes are there");
    std::string contents(bytes, '\0');
    in.read(contents.data(), bytes);
    if (crc32(contents) != crc)
      throw std::runtime_error(
        "it is damaged: the checksum of its contents does not match");
    return contents;
  }

  CheckpointState
  Checkpoint::read(const ResumingRun &run) const
  {
    if (!std::ifstream(path(), std::ios::binary))
      throw InputError(
        "Immersed cells/Resume",
        "true",
        "it needs the checkpoint " + path() +
          " of an earlier run, which does not exist or cannot be read.");
    CheckpointState state;
    try
      {
        std::istringstream              bytes(payload());
        boost::archive::binary_iarchive archive(bytes);
        archive >> state;
      }
    catch (const std::exception &e)
      {
        throw InputError("Immersed cells/Resume",
                         "true",
                         "the checkpoint " + path() +
                           " cannot be used: " + e.what() +
                           ". The one before it, if the run wrote two, is "
                           "checkpoint_previous.bin: rename it to "
                           "checkpoint.bin to resume from there.");
      }
    check_parameters(state.parameters, run);
    check_sizes(state, run);
    return state;
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
    if (state.n_ranks != run.n_ranks ||
        state.fluid.solution.size() != run.n_fluid_dofs ||
        state.positions.size() != run.n_cells ||
        state.positions[0].size() != run.n_point_values)
      throw InputError("Immersed cells/Resume",
                       "true",
                       "the checkpoint " + path() + " comes from a run on " +
                         std::to_string(state.n_ranks) + " rank(s) with " +
                         std::to_string(state.fluid.solution.size()) +
                         " fluid DoFs; this run has " +
                         std::to_string(run.n_ranks) + " rank(s) and " +
                         std::to_string(run.n_fluid_dofs) +
                         ": resume on the same number of ranks.");
    if (state.record.step >= run.n_steps)
      throw InputError("Time/Number of steps",
                       std::to_string(run.n_steps),
                       "a resumed run must go beyond the checkpoint's step " +
                         std::to_string(state.record.step) + ".");
  }
} // namespace rbc_ifem
