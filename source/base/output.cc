#include <rbc_ifem/base/input_error.h>
#include <rbc_ifem/base/output.h>
#include <rbc_ifem/base/output_error.h>

#include <deal.II/base/data_out_base.h>
#include <deal.II/base/mpi.h>
#include <deal.II/fe/mapping_q.h>
#include <deal.II/numerics/data_out.h>

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <map>
#include <memory>
#include <numeric>
#include <set>
#include <sstream>
#include <stdexcept>

namespace rbc_ifem
{
  DataOutBase::VtkFlags
  fast_vtk_flags()
  {
    DataOutBase::VtkFlags flags;
    flags.compression_level = DataOutBase::VtkFlags::best_speed;
    return flags;
  }

  FieldData
  frame_field_data(const double time,
                   const double frame_velocity,
                   const double frame_offset)
  {
    return {{"TIME", time},
            {"FRAME_VELOCITY", frame_velocity},
            {"FRAME_OFFSET", frame_offset}};
  }

  namespace
  {
    /// The VTU text @p data_out writes, with @p field_data as the
    /// <FieldData> of its grid (deal.II writes none unless asked for TIME
    /// or CYCLE through its flags, which we leave unset).
    template <int dim, int spacedim>
    std::string
    vtu_text(const DataOutInterface<dim, spacedim> &data_out,
             const FieldData                       &field_data)
    {
      std::ostringstream vtu;
      data_out.write_vtu(vtu);
      std::string       text = vtu.str();
      const std::string grid = "<UnstructuredGrid>";
      const std::size_t at   = text.find(grid);
      if (field_data.empty() || at == std::string::npos)
        return text;
      std::ostringstream data;
      data << std::setprecision(12) << "\n<FieldData>\n";
      for (const auto &[name, value] : field_data)
        data << "  <DataArray type=\"Float64\" Name=\"" << name
             << "\" NumberOfTuples=\"1\" format=\"ascii\">" << value
             << "</DataArray>\n";
      data << "</FieldData>";
      return text.insert(at + grid.size(), data.str());
    }
  } // namespace

  template <int dim, int spacedim>
  void
  write_vtu(const DataOutInterface<dim, spacedim> &data_out,
            const std::string                     &path,
            const FieldData                       &field_data)
  {
    write_text_atomically(path, vtu_text(data_out, field_data));
  }

  template <int dim, int spacedim>
  std::string
  write_vtu_pieces(const DataOutInterface<dim, spacedim> &data_out,
                   const std::string                     &directory,
                   const std::string                     &name,
                   const unsigned int                     counter,
                   const MPI_Comm                         communicator,
                   const FieldData                       &field_data)
  {
    std::vector<unsigned int> everyone(
      Utilities::MPI::n_mpi_processes(communicator));
    std::iota(everyone.begin(), everyone.end(), 0u);
    return write_vtu_pieces(
      data_out, directory, name, counter, everyone, communicator, field_data);
  }

  template <int dim, int spacedim>
  std::string
  write_vtu_pieces(const DataOutInterface<dim, spacedim> &data_out,
                   const std::string                     &directory,
                   const std::string                     &name,
                   const unsigned int                     counter,
                   const std::vector<unsigned int>       &writers,
                   const MPI_Comm                         communicator,
                   const FieldData                       &field_data)
  {
    Assert(std::is_sorted(writers.begin(), writers.end()),
           ExcMessage("The writers must be sorted."));
    const std::string stem  = name + "_" + Utilities::int_to_string(counter, 4);
    const auto        piece = [&](const unsigned int rank) {
      return stem + "." + Utilities::int_to_string(rank) + ".vtu";
    };
    const unsigned int rank = Utilities::MPI::this_mpi_process(communicator);
    write_vtu(data_out, directory + "/" + piece(rank), field_data);
    if (rank == writers.front())
      {
        std::vector<std::string> pieces;
        for (const unsigned int writer : writers)
          pieces.push_back(piece(writer));
        write_file_atomically(directory + "/" + stem + ".pvtu",
                              [&](std::ostream &out) {
                                data_out.write_pvtu_record(out, pieces);
                              });
      }
    return stem + ".pvtu";
  }

  template void
  write_vtu(const DataOutInterface<2, 3> &,
            const std::string &,
            const FieldData &);
  template void
  write_vtu(const DataOutInterface<3, 3> &,
            const std::string &,
            const FieldData &);
  template std::string
  write_vtu_pieces(const DataOutInterface<3, 3> &,
                   const std::string &,
                   const std::string &,
                   const unsigned int,
                   const MPI_Comm,
                   const FieldData &);
  template std::string
  write_vtu_pieces(const DataOutInterface<2, 3> &,
                   const std::string &,
                   const std::string &,
                   const unsigned int,
                   const std::vector<unsigned int> &,
                   const MPI_Comm,
                   const FieldData &);

  void
  write_pvd(const std::string                                 &directory,
            const std::string                                 &name,
            const std::vector<std::pair<double, std::string>> &records,
            const MPI_Comm                                     communicator,
            const unsigned int                                 writer)
  {
    if (Utilities::MPI::this_mpi_process(communicator) == writer)
      write_file_atomically(directory + "/" + name + ".pvd",
                            [&](std::ostream &out) {
                              DataOutBase::write_pvd_record(out, records);
                            });
  }

  void
  create_output_directory(const std::string &directory,
                          const MPI_Comm     communicator)
  {
    std::string problem;
    if (Utilities::MPI::this_mpi_process(communicator) == 0)
      {
        std::error_code error;
        std::filesystem::create_directories(directory, error);
        if (error)
          problem = error.message();
      }
    problem = Utilities::MPI::broadcast(communicator, problem, 0);
    if (!problem.empty())
      throw InputError("Output directory",
                       directory,
                       "it cannot be created: " + problem + ".");
  }

  namespace
  {
    /// Why no file can be created in @p directory or, if it does not
    /// exist, in its nearest existing parent; "" if one can.
    std::string
    why_not_writable(const std::string &directory)
    {
      namespace fs = std::filesystem;
      std::error_code error;
      fs::path folder = fs::absolute(directory, error).lexically_normal();
      while (!fs::exists(folder, error) && folder.has_parent_path() &&
             folder != folder.parent_path())
        folder = folder.parent_path();
      if (!fs::is_directory(folder, error))
        return folder.string() + " is not a folder";
      const std::string probe =
        (folder / (".rbc-ifem-write-check-" + std::to_string(::getpid())))
          .string();
      const int file = ::open(probe.c_str(), O_WRONLY | O_CREAT | O_EXCL, 0644);
      if (file < 0)
        return std::string(std::strerror(errno)) + " (in " + folder.string() +
               ")";
      ::close(file);
      ::unlink(probe.c_str());
      return "";
    }
  } // namespace

  void
  check_writable(const std::string &directory, const MPI_Comm communicator)
  {
    std::string problem;
    if (Utilities::MPI::this_mpi_process(communicator) == 0)
      problem = why_not_writable(directory);
    problem = Utilities::MPI::broadcast(communicator, problem, 0);
    if (!problem.empty())
      throw InputError("Output directory",
                       directory,
                       "no file can be written there: " + problem + ".");
  }

  namespace
  {
    /// Every file write_file_atomically() has written in this process.
    std::set<std::filesystem::path> &
    files_written_so_far()
    {
      static std::set<std::filesystem::path> files;
      return files;
    }

    /// @p path without "." components and trailing separators.
    std::filesystem::path
    normal_path(const std::string &path)
    {
      std::filesystem::path normal =
        std::filesystem::path(path).lexically_normal();
      if (!normal.has_filename())
        normal = normal.parent_path();
      return normal;
    }
  } // namespace

  std::string
  written_files(const std::string &directory, const MPI_Comm communicator)
  {
    // Each rank's files in @p directory but the VTU pieces, relative to it:
    // rank 0 lists them all, once.
    const std::filesystem::path top = normal_path(directory);
    std::vector<std::string>    mine;
    for (const std::filesystem::path &file : files_written_so_far())
      {
        const std::filesystem::path relative = file.lexically_relative(top);
        if (!relative.empty() && *relative.begin() != ".." &&
            file.extension() != ".vtu" && file.extension() != ".pvtu")
          mine.push_back(relative.string());
      }
    std::set<std::filesystem::path> files;
    for (const auto &rank_files : Utilities::MPI::gather(communicator, mine, 0))
      files.insert(rank_files.begin(), rank_files.end());
    std::vector<std::string>            names;
    std::map<std::string, unsigned int> subdirectories;
    for (const std::filesystem::path &relative : files)
      {
        const std::string first = relative.begin()->string();
        if (relative.has_parent_path())
          ++subdirectories[first];
        else
          names.push_back(first);
      }
    std::string list;
    const auto  append = [&list](const std::string &item) {
      list += (list.empty() ? "" : ", ") + item;
    };
    for (const std::string &name : names)
      append(name);
    for (const auto &[name, count] : subdirectories)
      append(name + "/ (" + std::to_string(count) + " files)");
    return list;
  }

  void
  write_parameters(const std::string &text,
                   const std::string &directory,
                   const MPI_Comm     communicator)
  {
    create_output_directory(directory, communicator);
    if (Utilities::MPI::this_mpi_process(communicator) == 0)
      write_file_atomically(directory + "/parameters.prm",
                            [&](std::ostream &out) { out << text; });
  }

  namespace
  {
    /// Write @p bytes as @p path, fsync'ed if @p sync; OutputError with
    /// errno's text, and no file left at @p path, if that fails.
    /// Write @p bytes at @p offset of the open @p file; 0 or the errno.
    int
    write_at(const int           file,
             const std::string  &bytes,
             const std::uint64_t offset)
    {
      std::size_t written = 0;
      while (written < bytes.size())
        {
          const ssize_t n = ::pwrite(file,
                                     bytes.data() + written,
                                     bytes.size() - written,
                                     offset + written);
          if (n < 0 && errno != EINTR)
            return errno;
          if (n > 0)
            written += n;
        }
      return 0;
    }

    /// fsync (if @p sync) and close @p file after @p error (0 or an
    /// errno); the first error of the three.
    int
    finish(const int file, int error, const bool sync)
    {
      if (error == 0 && sync && ::fsync(file) != 0)
        error = errno;
      if (::close(file) != 0 && error == 0)
        error = errno;
      return error;
    }

    void
    write_bytes(const std::string &path,
                const std::string &bytes,
                const bool         sync)
    {
      const int file = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
      if (file < 0)
        throw OutputError(path, std::strerror(errno));
      if (const int error = finish(file, write_at(file, bytes, 0), sync);
          error != 0)
        {
          ::unlink(path.c_str());
          throw OutputError(path, std::strerror(error));
        }
    }
  } // namespace

  void
  write_synced_file(const std::string &path, const std::string &bytes)
  {
    write_bytes(path, bytes, true);
  }

  void
  write_in_rank_order(const std::string &path,
                      const std::string &head,
                      const std::string &block,
                      const MPI_Comm     communicator)
  {
    const bool first = Utilities::MPI::this_mpi_process(communicator) == 0;
    const std::uint64_t size   = block.size();
    std::uint64_t       offset = 0;
    MPI_Exscan(&size, &offset, 1, MPI_UINT64_T, MPI_SUM, communicator);
    // Rank 0 makes the file (empty, whatever was there) before the others
    // open it; each rank then writes its part where it goes, at once.
    int error = 0, file = -1;
    if (first)
      {
        file  = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
        error = file < 0 ? errno : write_at(file, head, 0);
      }
    const std::uint64_t head_size =
      Utilities::MPI::broadcast(communicator,
                                static_cast<std::uint64_t>(head.size()),
                                0);
    if (!first)
      {
        file  = ::open(path.c_str(), O_WRONLY);
        error = file < 0 ? errno : 0;
      }
    if (error == 0)
      error = write_at(file, block, head_size + (first ? 0 : offset));
    if (file >= 0)
      error = finish(file, error, true);
    // What any rank failed to write leaves no file that looks complete.
    if (Utilities::MPI::logical_or(error != 0, communicator) && first)
      ::unlink(path.c_str());
    if (error != 0)
      throw OutputError(path, std::strerror(error));
  }

  void
  rename_written_file(const std::string &from, const std::string &to)
  {
    if (std::rename(from.c_str(), to.c_str()) != 0)
      {
        const int error = errno;
        ::unlink(from.c_str());
        throw OutputError(to, std::strerror(error));
      }
    files_written_so_far().insert(normal_path(to));
  }

  void
  write_text_atomically(const std::string &path, const std::string &text)
  {
    const std::string temporary = path + ".part";
    write_bytes(temporary, text, false);
    rename_written_file(temporary, path);
  }

  void
  write_file_atomically(const std::string                         &path,
                        const std::function<void(std::ostream &)> &writer)
  {
    std::ostringstream text;
    writer(text);
    write_text_atomically(path, text.str());
  }

  namespace
  {
    /// The boundary faces this rank owns, one patch each, with their id.
    std::vector<DataOutBase::Patch<2, 3>>
    boundary_patches(const Triangulation<3> &triangulation)
    {
      std::vector<DataOutBase::Patch<2, 3>> patches;
      for (const auto &cell : triangulation.active_cell_iterators())
        if (cell->is_locally_owned())
          for (const auto &face : cell->face_iterators())
            if (face->at_boundary())
              {
                DataOutBase::Patch<2, 3> patch;
                patch.reference_cell = face->reference_cell();
                for (const unsigned int v : face->vertex_indices())
                  patch.vertices[v] = face->vertex(v);
                patch.data.reinit(1, face->n_vertices());
                for (unsigned int v = 0; v < face->n_vertices(); ++v)
                  patch.data(0, v) = face->boundary_id();
                patch.patch_index = patches.size();
                patches.push_back(patch);
              }
      return patches;
    }
  } // namespace

  void
  write_volume_mesh(const Triangulation<3> &triangulation,
                    const std::string      &directory,
                    const std::string      &name,
                    const MPI_Comm          communicator)
  {
    Vector<float> material_id(triangulation.n_active_cells());
    Vector<float> owner(triangulation.n_active_cells());
    for (const auto &cell : triangulation.active_cell_iterators())
      {
        material_id[cell->active_cell_index()] = cell->material_id();
        owner[cell->active_cell_index()]       = cell->subdomain_id();
      }
    DataOut<3> data_out;
    data_out.attach_triangulation(triangulation);
    data_out.set_flags(fast_vtk_flags());
    data_out.add_data_vector(material_id,
                             "material_id",
                             DataOut<3>::type_cell_data);
    data_out.add_data_vector(owner, "rank", DataOut<3>::type_cell_data);
    // Curved cells, so the circles look like circles in ParaView.
    data_out.build_patches(MappingQ<3>(2), 2, DataOut<3>::curved_inner_cells);
    const std::string pvtu =
      write_vtu_pieces(data_out, directory, name, 0, communicator);

    // The boundary: one piece per rank, joined by a pvtu record on rank 0.
    const unsigned int rank    = Utilities::MPI::this_mpi_process(communicator);
    const unsigned int n_ranks = Utilities::MPI::n_mpi_processes(communicator);
    const auto         piece   = [&](const unsigned int r) {
      return name + "_boundary." + Utilities::int_to_string(r, 4) + ".vtu";
    };
    const auto patches = boundary_patches(triangulation);
    write_file_atomically(directory + "/" + piece(rank),
                          [&](std::ostream &out) {
                            DataOutBase::write_vtu(patches,
                                                   {"boundary_id"},
                                                   {},
                                                   fast_vtk_flags(),
                                                   out);
                          });

    if (rank == 0)
      {
        std::vector<std::string> pieces;
        for (unsigned int r = 0; r < n_ranks; ++r)
          pieces.push_back(piece(r));
        write_file_atomically(
          directory + "/" + name + "_boundary.pvtu", [&](std::ostream &out) {
            DataOutBase::write_pvtu_record(
              out, pieces, {"boundary_id"}, {}, fast_vtk_flags());
          });
        write_pvd(directory, name, {{0., pvtu}}, communicator);
        write_pvd(directory,
                  name + "_boundary",
                  {{0., name + "_boundary.pvtu"}},
                  communicator);
      }
  }

  std::string
  write_membranes(
    const std::vector<const Triangulation<2, 3> *>           &surfaces,
    const MappingQ<2, 3>                                     &mapping,
    const std::string                                        &directory,
    const std::string                                        &name,
    const MPI_Comm                                            communicator,
    const std::function<void(unsigned int, DataOut<2, 3> &)> &add_fields,
    const FieldData                                          &field_data)
  {
    const std::string file = name + ".vtu";
    if (Utilities::MPI::this_mpi_process(communicator) != 0 || surfaces.empty())
      return file;

    // One DataOut per membrane; the patches of all go into the first.
    std::vector<Vector<float>>                  cell_index(surfaces.size());
    std::vector<std::unique_ptr<DataOut<2, 3>>> outputs;
    for (unsigned int i = 0; i < surfaces.size(); ++i)
      {
        cell_index[i].reinit(surfaces[i]->n_active_cells());
        cell_index[i] = i;
        outputs.push_back(std::make_unique<DataOut<2, 3>>());
        DataOut<2, 3> &data_out = *outputs.back();
        data_out.attach_triangulation(*surfaces[i]);
        data_out.add_data_vector(cell_index[i],
                                 "cell",
                                 DataOut<2, 3>::type_cell_data);
        if (add_fields)
          add_fields(i, data_out);
        data_out.build_patches(mapping,
                               mapping.get_degree(),
                               DataOut<2, 3>::curved_inner_cells);
        if (i > 0)
          outputs[0]->merge_patches(data_out);
      }
    DataOut<2, 3> &all = *outputs[0];
    all.set_flags(fast_vtk_flags());
    write_vtu(all, directory + "/" + file, field_data);
    return file;
  }

  std::string
  duration_text(const double seconds)
  {
    std::ostringstream text;
    const long         whole = std::lround(seconds);
    if (seconds < 60.)
      text << std::setprecision(seconds < 10. ? 2 : 3) << seconds << " s";
    else if (whole < 3600)
      text << whole / 60 << " min " << std::setw(2) << std::setfill('0')
           << whole % 60 << " s";
    else
      text << whole / 3600 << " h " << std::setw(2) << std::setfill('0')
           << whole % 3600 / 60 << " min";
    return text.str();
  }

  std::string
  time_left_text(const double       elapsed,
                 const unsigned int done,
                 const unsigned int left)
  {
    std::string text = "[wall " + duration_text(elapsed);
    if (done > 0)
      text += ", about " + duration_text(elapsed / done * left) + " left";
    return text + "]";
  }

  std::string
  peak_memory_text(const MPI_Comm communicator)
  {
    Utilities::System::MemoryStats memory;
    Utilities::System::get_memory_stats(memory);
    const double mb      = memory.VmHWM / 1024.;
    const bool   first   = Utilities::MPI::this_mpi_process(communicator) == 0;
    const double largest = Utilities::MPI::max(mb, communicator);
    std::ostringstream text;
    text << largest << " MB (largest over ranks";
    if (Utilities::MPI::n_mpi_processes(communicator) > 1)
      {
        // Rank 0 left out of the others' range: it gives the largest to
        // their least and nothing to their most.
        const double least =
          Utilities::MPI::min(first ? largest : mb, communicator);
        const double most = Utilities::MPI::max(first ? 0. : mb, communicator);
        text << "; rank 0 " << Utilities::MPI::broadcast(communicator, mb, 0)
             << " MB, the others " << least << "-" << most << " MB";
      }
    return text.str() + ")";
  }

  void
  write_timing(const TimerOutput &timer,
               const std::string &directory,
               const MPI_Comm     communicator)
  {
    if (Utilities::MPI::this_mpi_process(communicator) != 0)
      return;
    const auto wall  = timer.get_summary_data(TimerOutput::total_wall_time);
    const auto calls = timer.get_summary_data(TimerOutput::n_calls);
    write_file_atomically(directory + "/timing.csv", [&](std::ostream &out) {
      out << "section,calls,wall_seconds\n";
      for (const auto &[section, seconds] : wall)
        out << '"' << section << "\"," << calls.at(section) << ',' << seconds
            << '\n';
    });
  }
} // namespace rbc_ifem
