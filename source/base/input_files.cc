#include <rbc_ifem/base/input_files.h>
#include <rbc_ifem/base/output.h>
#include <rbc_ifem/base/output_error.h>
#include <rbc_ifem/base/parameter_text.h>

#include <deal.II/base/utilities.h>

#include <filesystem>
#include <fstream>
#include <sstream>

namespace rbc_ifem
{
  namespace
  {
    /// The whole content of the file @p path.
    std::string
    file_bytes(const std::string &path)
    {
      std::ifstream in(path, std::ios::binary);
      if (!in)
        throw OutputError(path, "it cannot be read to copy it");
      std::ostringstream bytes;
      bytes << in.rdbuf();
      return bytes.str();
    }
  } // namespace

  void
  resolve_file_parameters(ParameterHandler &prm, const std::string &folder)
  {
    if (folder.empty())
      return;
    const auto values = parameter_values(parameter_text(prm));
    for (const auto &[path, pattern] : parameter_patterns(prm))
      if (pattern.rfind("[FileName", 0) == 0)
        {
          const std::string &value = values.at(path);
          if (!value.empty() && std::filesystem::path(value).is_relative())
            set_entry(prm,
                      path,
                      (std::filesystem::path(folder) / value)
                        .lexically_normal()
                        .string());
        }
  }

  std::string
  copy_name(const InputFile &input)
  {
    return "inputs/" + std::filesystem::path(input.path).filename().string();
  }

  std::string
  with_input_copies(const std::string            &text,
                    const std::vector<InputFile> &inputs)
  {
    std::string result;
    for (const ParameterLine &line : parameter_lines(text))
      {
        std::string written = line.text;
        for (const InputFile &input : inputs)
          if (line.kind == ParameterLine::Kind::set &&
              input.entry == line.prefix + line.name)
            written = line.text.substr(0, line.text.find('=') + 1) + " " +
                      copy_name(input);
        result += written + '\n';
      }
    return result;
  }

  void
  copy_input_files(const std::vector<InputFile> &inputs,
                   const std::string            &directory,
                   const bool                    keep_existing,
                   const MPI_Comm                communicator)
  {
    if (Utilities::MPI::this_mpi_process(communicator) != 0)
      return;
    for (const InputFile &input : inputs)
      {
        const std::string copy = directory + "/" + copy_name(input);
        std::error_code   error;
        if (std::filesystem::equivalent(input.path, copy, error) ||
            (keep_existing && std::filesystem::exists(copy)))
          continue;
        std::filesystem::create_directories(directory + "/inputs", error);
        write_text_atomically(copy, file_bytes(input.path));
      }
  }
} // namespace rbc_ifem
