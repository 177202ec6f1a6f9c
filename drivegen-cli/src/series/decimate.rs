//! Fewer points for a long series: a plot of a million samples would be a file of tens of
//! megabytes that no browser draws smoothly, and a screen only has so many columns. The time
//! axis is cut into buckets and each keeps its first, lowest, highest and last sample in time
//! order, so every spike and every level the line reaches stays visible.

/// Buckets across the time axis: several per pixel of the plot, so the HTML page's zoom still
/// finds detail.
pub const BUCKETS: usize = 4096;

/// `samples` (in time order) reduced to at most four per bucket of `[low, high]`; unchanged when
/// there are few.
pub fn decimate(samples: &[(f64, f64)], low: f64, high: f64) -> Vec<(f64, f64)> {
    if samples.len() <= 4 * BUCKETS || high <= low {
        return samples.to_vec();
    }
    let bucket = |t: f64| {
        (((t - low) / (high - low)) * BUCKETS as f64).clamp(0.0, BUCKETS as f64 - 1.0) as usize
    };
    let mut out = Vec::with_capacity(4 * BUCKETS);
    let mut start = 0;
    while start < samples.len() {
        let which = bucket(samples[start].0);
        let end = start
            + samples[start..]
                .iter()
                .take_while(|s| bucket(s.0) == which)
                .count();
        keep_extremes(&samples[start..end], &mut out);
        start = end;
    }
    out
}

/// The first, lowest, highest and last sample of a bucket, each once, in time order.
fn keep_extremes(bucket: &[(f64, f64)], out: &mut Vec<(f64, f64)>) {
    let last = bucket.len() - 1;
    let by_value = |a: &&(usize, &(f64, f64)), b: &&(usize, &(f64, f64))| a.1 .1.total_cmp(&b.1 .1);
    let indexed: Vec<(usize, &(f64, f64))> = bucket.iter().enumerate().collect();
    let lowest = indexed.iter().min_by(by_value).map_or(0, |p| p.0);
    let highest = indexed.iter().max_by(by_value).map_or(0, |p| p.0);
    let mut kept = [0, lowest, highest, last];
    kept.sort_unstable();
    let mut previous = None;
    for i in kept {
        if previous != Some(i) {
            out.push(bucket[i]);
            previous = Some(i);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_long_series_keeps_its_spikes_and_ends() {
        let mut samples: Vec<(f64, f64)> = (0..100_000).map(|i| (i as f64, 0.0)).collect();
        samples[54_321].1 = 1000.0;
        samples[77_777].1 = -5.0;
        let kept = decimate(&samples, 0.0, 99_999.0);
        assert!(kept.len() <= 4 * BUCKETS, "{}", kept.len());
        assert!(kept.contains(&(54_321.0, 1000.0)));
        assert!(kept.contains(&(77_777.0, -5.0)));
        assert_eq!(kept.first(), samples.first());
        assert_eq!(kept.last(), samples.last());
        assert!(kept.windows(2).all(|w| w[0].0 < w[1].0), "time order");
    }

    #[test]
    fn a_short_series_is_left_alone() {
        let samples = [(0.0, 1.0), (1.0, 2.0)];
        assert_eq!(decimate(&samples, 0.0, 1.0), samples);
    }
}
