// The task runner and its journal: results independent of the threads, a stop flag that ends the
// run after the tasks under way, a resumed journal whose tasks are not computed again.
#include "sympathy/continuation/task_runner.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <random>

#include "sympathy/continuation/task_journal.hpp"
#include "sympathy/core/errors.hpp"

namespace sympathy {
namespace {

// A task whose work is random from its seed and uneven in length (up to 20,000 draws).
std::optional<std::vector<std::string>> draws(std::size_t index) {
  std::mt19937_64 generator(task_seed(7, index));
  const int n = 1 + static_cast<int>(generator() % 20000);
  double sum = 0.0;
  for (int i = 0; i < n; ++i) sum += unit_uniform(generator());
  return std::vector<std::string>{std::to_string(n), std::to_string(sum)};
}

std::map<std::size_t, std::vector<std::string>> run_on(int threads, std::size_t count) {
  std::map<std::size_t, std::vector<std::string>> results;
  TaskRunOptions o;
  o.threads = threads;
  const auto summary = run_tasks<std::vector<std::string>>(
      count, {}, draws,
      [&](std::size_t i, std::vector<std::string>&& r) { results.emplace(i, std::move(r)); }, o);
  EXPECT_EQ(summary.computed, count);
  EXPECT_FALSE(summary.interrupted);
  return results;
}

TEST(TaskRunner, ResultsDoNotDependOnTheThreads) {
  const auto one = run_on(1, 200);
  EXPECT_EQ(one.size(), 200u);
  EXPECT_EQ(run_on(2, 200), one);
  EXPECT_EQ(run_on(5, 200), one);
  // Neighbouring tasks and seeds draw unrelated streams.
  EXPECT_NE(task_seed(7, 0), task_seed(7, 1));
  EXPECT_NE(task_seed(7, 1), task_seed(8, 0));
  EXPECT_NE(task_seed(7, 0), task_seed(8, 0));
}

TEST(TaskRunner, StopFlagEndsTheRunAfterTheTasksUnderWay) {
  std::atomic<bool> stop{false};
  std::size_t recorded = 0;
  TaskRunOptions o;
  o.threads = 2;
  const auto summary = run_tasks<int>(
      100, {},
      [&](std::size_t i) -> std::optional<int> {
        if (i == 10) stop = true;
        return static_cast<int>(i);
      },
      [&](std::size_t, int&&) { ++recorded; }, o, &stop);
  EXPECT_TRUE(summary.interrupted);
  EXPECT_EQ(summary.computed, recorded);
  EXPECT_LE(recorded, 12u);  // task 10 and at most one more under way on the other thread
}

TEST(TaskRunner, AnErrorStopsTheRunAndIsRethrown) {
  TaskRunOptions o;
  o.threads = 2;
  EXPECT_THROW(run_tasks<int>(
                   50, {},
                   [](std::size_t i) -> std::optional<int> {
                     if (i == 3) throw std::runtime_error("task 3 failed");
                     return 0;
                   },
                   [](std::size_t, int&&) {}, o),
               std::runtime_error);
  o.threads = -1;
  EXPECT_EQ(o.validate()->field, "threads");
}

class TaskJournalTest : public ::testing::Test {
 protected:
  std::string path = (std::filesystem::temp_directory_path() /
                      ("sympathy_journal_" +
                       std::to_string(::testing::UnitTest::GetInstance()->random_seed()) + ".csv"))
                         .string();
  void TearDown() override { std::filesystem::remove(path); }
};

// A run killed after some tasks, resumed: only the others are computed, and the table (in task
// order) equals an uninterrupted run's.
TEST_F(TaskJournalTest, ResumeComputesOnlyTheTasksNotInTheJournal) {
  const std::size_t count = 40;
  {
    TaskJournal journal(path, {"n", "sum"}, count, false);
    for (std::size_t i : {3u, 0u, 17u, 8u}) journal.append(i, *draws(i));
    journal.close();
  }
  {  // A kill in the middle of a row leaves a cut line: dropped on resume.
    std::ofstream(path, std::ios::app) << "25,99";
  }
  TaskJournal journal(path, {"n", "sum"}, count, true);
  EXPECT_EQ(journal.resumed(), 4u);
  std::atomic<std::size_t> computed{0};
  TaskRunOptions o;
  o.threads = 2;
  const auto summary = run_tasks<std::vector<std::string>>(
      count, journal.done(),
      [&](std::size_t i) {
        ++computed;
        return draws(i);
      },
      [&](std::size_t i, std::vector<std::string>&& r) { journal.append(i, std::move(r)); }, o);
  journal.close();
  EXPECT_EQ(summary.skipped, 4u);
  EXPECT_EQ(summary.computed, count - 4);
  EXPECT_EQ(computed.load(), count - 4);  // the work itself ran only for the tasks not journaled

  std::string whole;
  for (const auto& [i, r] : run_on(1, count))
    whole += std::to_string(i) + "," + r[0] + "," + r[1] + "\n";
  EXPECT_EQ(journal.table(), "task,n,sum\n" + whole);
  // The file holds every task once: reopening it finds them all.
  EXPECT_EQ(TaskJournal(path, {"n", "sum"}, count, true).resumed(), count);
}

TEST_F(TaskJournalTest, AJournalOfAnotherRunIsRefused) {
  {
    TaskJournal journal(path, {"n", "sum"}, 10, false);
    journal.append(9, {"1", "2"});
  }
  EXPECT_THROW(TaskJournal(path, {"n", "mean"}, 10, true), InputError);  // another header
  EXPECT_THROW(TaskJournal(path, {"n", "sum"}, 5, true), InputError);    // task 9 of 5
  TaskJournal journal(path, {"n", "sum"}, 10, true);
  EXPECT_THROW(journal.append(9, {"1", "2"}), std::invalid_argument);  // twice
  EXPECT_THROW(journal.append(1, {"1,5", "2"}), std::invalid_argument);
}

}  // namespace
}  // namespace sympathy
