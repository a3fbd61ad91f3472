#include <yarn_impact/core/reproducible_sum.h>

#include <cmath>
#include <stdexcept>

namespace YarnImpact
{
  namespace
  {
    using Bins = ReproducibleSum::Bins;

    /** Add @p from into @p to (exact: integer digits on a common grid). */
    void
    merge_bins(const Bins &from, Bins &to)
    {
      to.non_finite += from.non_finite;
      if (from.top < 0)
        return;
      if (from.top > to.top)
        to.raise_top(from.top);
      Bins aligned = from;
      if (aligned.top < to.top)
        aligned.raise_top(to.top);
      for (int k = 0; k < ReproducibleSum::n_kept_bins; ++k)
        to.words[k] += aligned.words[k];
    }


    /** The value of @p b rounded to double: the same bits for the same
     * @p b. */
    double
    round_bins(Bins b)
    {
      constexpr int K          = ReproducibleSum::n_kept_bins;
      constexpr int bin_width  = ReproducibleSum::bin_width;
      constexpr int bin_offset = ReproducibleSum::bin_offset;
      if (!(b.non_finite == 0.))
        return b.non_finite;
      if (b.top < 0)
        return 0.;
      // Carry each word's overflow into the next: all words but the
      // highest in [0, 2^32), which keeps the sign.
      for (int k = 0; k < K - 1; ++k)
        {
          const std::int64_t carry = b.words[k] >> bin_width; // floor
          b.words[k] -= carry * (std::int64_t(1) << bin_width);
          b.words[k + 1] += carry;
        }
      // The three highest words as one integer, rounded once to double;
      // the lowest word (below 2^-64 of the largest term) only through
      // its carries.
      using int128 = ReproducibleSum::int128;
      const int128 high =
        static_cast<int128>(b.words[K - 1]) * (static_cast<int128>(1) << 64) +
        static_cast<int128>(b.words[K - 2]) * (static_cast<int128>(1) << 32) +
        b.words[K - 3];
      const int exponent =
        static_cast<int>((b.top - K + 2) * bin_width - bin_offset);
      return std::ldexp(static_cast<double>(high), exponent);
    }


    void
    merge_op(void *in, void *inout, int *len, MPI_Datatype *)
    {
      const Bins *from = static_cast<const Bins *>(in);
      Bins *to         = static_cast<Bins *>(inout);
      for (int i = 0; i < *len; ++i)
        merge_bins(from[i], to[i]);
    }
  } // namespace


  ReproducibleSum::ReproducibleSum(const unsigned int n_values)
    : bins(n_values)
  {}


  void
  ReproducibleSum::merge(const ReproducibleSum &other)
  {
    if (other.size() != size())
      throw std::logic_error("ReproducibleSum::merge: sizes differ");
    for (unsigned int i = 0; i < size(); ++i)
      merge_bins(other.bins[i], bins[i]);
  }


  std::vector<double>
  ReproducibleSum::local_values() const
  {
    std::vector<double> values(size());
    for (unsigned int i = 0; i < size(); ++i)
      values[i] = round_bins(bins[i]);
    return values;
  }


  std::vector<double>
  ReproducibleSum::sum(const MPI_Comm communicator) const
  {
    int n_ranks = 1;
    MPI_Comm_size(communicator, &n_ranks);
    if (n_ranks == 1 || size() == 0)
      return local_values();
    // One element per sum, moved as bytes and merged by merge_op (which is
    // commutative and associative: the merge is exact).
    MPI_Datatype type;
    MPI_Type_contiguous(sizeof(Bins), MPI_BYTE, &type);
    MPI_Type_commit(&type);
    MPI_Op op;
    MPI_Op_create(&merge_op, 1, &op);
    std::vector<Bins> global(size());
    const int error =
      MPI_Allreduce(bins.data(), global.data(), size(), type, op, communicator);
    MPI_Op_free(&op);
    MPI_Type_free(&type);
    if (error != MPI_SUCCESS)
      throw std::runtime_error("ReproducibleSum::sum: MPI_Allreduce failed");
    std::vector<double> values(size());
    for (unsigned int i = 0; i < size(); ++i)
      values[i] = round_bins(global[i]);
    return values;
  }


  double
  reproducible_sum(const std::vector<double> &terms,
                   const MPI_Comm communicator)
  {
    ReproducibleSum s;
    for (const double t : terms)
      s.add(0, t);
    return s.sum(communicator)[0];
  }
} // namespace YarnImpact
