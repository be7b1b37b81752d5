#include <deal.II/base/exceptions.h>

#include <impactfe/utilities/program.h>

#include <iostream>
#include <sstream>

namespace impactfe
{
  std::string
  format_number(const double value)
  {
    std::ostringstream s;
    s << value;
    return s.str();
  }



  int
  report_exception(const std::exception &exc)
  {
    std::cerr << std::endl
              << "----------------------------------------------------"
              << std::endl
              << "Exception on processing: " << std::endl;
    if (const auto *deal_exc = dynamic_cast<const dealii::ExceptionBase *>(&exc))
      deal_exc->print_info(std::cerr);
    else
      std::cerr << exc.what() << std::endl;
    std::cerr << "Aborting!" << std::endl
              << "----------------------------------------------------"
              << std::endl;
    return 1;
  }



  int
  report_unknown_exception()
  {
    std::cerr << std::endl
              << "----------------------------------------------------"
              << std::endl
              << "Unknown exception!" << std::endl
              << "Aborting!" << std::endl
              << "----------------------------------------------------"
              << std::endl;
    return 1;
  }
} // namespace impactfe
