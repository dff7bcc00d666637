// Hot paths do not allocate: a built-in MCP's F and Jacobian, evaluated again at the same size, touch no heap
// (backends call them every iteration). Its own binary: tests/support/malloc_counter interposes malloc.
#include <gtest/gtest.h>

#include "problems/mcp/mcp_suite.h"
#include "tests/support/malloc_counter.h"

namespace smcbench {
namespace {

TEST(McpAllocationTest, EvaluateAndJacobianDoNotAllocateOnceSized) {
  if (!test_support::CanCountMallocs()) GTEST_SKIP() << "allocations cannot be observed in this build";
  std::vector<std::string> ids = McpSuiteIds(true);
  ids.push_back("mcp/obstacle2d/m100");
  for (const std::string& id : ids) {
    SCOPED_TRACE(id);
    const std::shared_ptr<const MCP> p = MakeBuiltinMcp(id);
    const Vector z = (p->l().array().isFinite()).select(p->l(), 0.0) + Vector::Constant(p->size(), 0.5);
    Vector F(p->size());
    DenseMatrix J;
    SparseMatrix S;
    const bool sparse = p->jacobian_kind() == MCP::JacobianKind::kSparse;
    const auto call = [&] {
      p->Evaluate(z, &F);
      if (sparse) {
        p->JacobianSparse(z, &S);
      } else {
        p->JacobianDense(z, &J);
      }
    };
    call();  // sizes the outputs
    EXPECT_EQ(test_support::CountMallocs(call), 0);
  }
}

}  // namespace
}  // namespace smcbench
