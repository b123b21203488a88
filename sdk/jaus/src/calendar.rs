//! UTC as a calendar date and time of day, and back: what the time and date stamps of
//! RA 3.3 and AS-4 (Report Time, Set Time, the stamps of sensor reports) carry. Pure
//! arithmetic on the proleptic Gregorian calendar; no clock is read here.

use std::time::Duration;

const DAY_MS: u64 = 86_400_000;

/// A UTC instant as date and time of day (milliseconds kept).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Civil {
    /// Year (e.g. 2026).
    pub year: i64,
    /// Month, 1–12.
    pub month: u32,
    /// Day of the month, 1–31.
    pub day: u32,
    /// Hour, 0–23.
    pub hour: u32,
    /// Minute, 0–59.
    pub minute: u32,
    /// Second, 0–59.
    pub second: u32,
    /// Millisecond, 0–999.
    pub millisecond: u32,
}

impl Civil {
    /// The date and time `utc` after 1970-01-01T00:00:00Z.
    ///
    /// ```
    /// use jaus::calendar::Civil;
    /// use std::time::Duration;
    ///
    /// let c = Civil::from_utc(Duration::from_millis(1_795_000_000_123));
    /// assert_eq!((c.year, c.month, c.day, c.hour, c.minute, c.second, c.millisecond),
    ///            (2026, 11, 18, 11, 6, 40, 123));
    /// assert_eq!(c.to_utc(), Ok(Duration::from_millis(1_795_000_000_123)));
    /// ```
    pub fn from_utc(utc: Duration) -> Civil {
        let ms = u64::try_from(utc.as_millis()).unwrap_or(u64::MAX);
        let (year, month, day) = civil_from_days((ms / DAY_MS) as i64);
        let tod = ms % DAY_MS;
        Civil {
            year,
            month,
            day,
            hour: (tod / 3_600_000) as u32,
            minute: (tod / 60_000 % 60) as u32,
            second: (tod / 1000 % 60) as u32,
            millisecond: (tod % 1000) as u32,
        }
    }

    /// The time since 1970-01-01T00:00:00Z; the error names an impossible date or time
    /// (30 February, 24:00, a date before 1970).
    pub fn to_utc(&self) -> Result<Duration, String> {
        if self.hour > 23 || self.minute > 59 || self.second > 59 || self.millisecond > 999 {
            return Err(format!(
                "impossible time {:02}:{:02}:{:02}.{:03}",
                self.hour, self.minute, self.second, self.millisecond
            ));
        }
        if !(1..=12).contains(&self.month)
            || self.day == 0
            || self.day > days_in_month(self.year, self.month)
        {
            return Err(format!(
                "impossible date {}-{:02}-{:02}",
                self.year, self.month, self.day
            ));
        }
        let days = u64::try_from(days_from_civil(self.year, self.month, self.day))
            .map_err(|_| format!("date {} before 1970", self.year))?;
        let tod = ((u64::from(self.hour) * 60 + u64::from(self.minute)) * 60
            + u64::from(self.second))
            * 1000
            + u64::from(self.millisecond);
        Ok(Duration::from_millis(days * DAY_MS + tod))
    }
}

/// Whether `y` is a leap year.
pub fn is_leap(y: i64) -> bool {
    y % 4 == 0 && (y % 100 != 0 || y % 400 == 0)
}

/// Days in month `m` (1–12) of year `y`; 0 for a month that does not exist.
pub fn days_in_month(y: i64, m: u32) -> u32 {
    match m {
        1 | 3 | 5 | 7 | 8 | 10 | 12 => 31,
        4 | 6 | 9 | 11 => 30,
        2 if is_leap(y) => 29,
        2 => 28,
        _ => 0,
    }
}

/// Days since 1970-01-01 of a proleptic Gregorian date (counted from 1 March so that
/// the leap day falls last in each counted year, in 400-year cycles).
pub fn days_from_civil(y: i64, m: u32, d: u32) -> i64 {
    let y = if m <= 2 { y - 1 } else { y };
    let era = y.div_euclid(400);
    let yoe = y - era * 400;
    let mp = (i64::from(m) + 9) % 12;
    let doy = (153 * mp + 2) / 5 + i64::from(d) - 1;
    let doe = yoe * 365 + yoe / 4 - yoe / 100 + doy;
    era * 146_097 + doe - 719_468
}

/// The date of a day count since 1970-01-01 (the inverse of [`days_from_civil`]).
pub fn civil_from_days(z: i64) -> (i64, u32, u32) {
    let z = z + 719_468;
    let era = z.div_euclid(146_097);
    let doe = z - era * 146_097;
    let yoe = (doe - doe / 1460 + doe / 36_524 - doe / 146_096) / 365;
    let doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    let mp = (5 * doy + 2) / 153;
    let d = (doy - (153 * mp + 2) / 5 + 1) as u32;
    let m = if mp < 10 { mp + 3 } else { mp - 9 } as u32;
    let y = yoe + era * 400 + i64::from(m <= 2);
    (y, m, d)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn calendar_conversion_matches_known_dates() {
        assert_eq!(days_from_civil(1970, 1, 1), 0);
        assert_eq!(days_from_civil(2000, 3, 1), 11_017);
        // 2026-11-22 is 20,779 days after the epoch.
        assert_eq!(days_from_civil(2026, 11, 22), 20_779);
        for z in [0, 59, 60, 11_016, 11_017, 20_779, 47_541] {
            let (y, m, d) = civil_from_days(z);
            assert_eq!(days_from_civil(y, m, d), z);
        }
        assert_eq!(civil_from_days(11_016), (2000, 2, 29));
        assert_eq!(civil_from_days(47_541), (2100, 3, 1));
    }

    #[test]
    fn impossible_dates_and_times_are_named() {
        let ok = Civil::from_utc(Duration::from_secs(1_795_000_000));
        assert!(Civil {
            month: 2,
            day: 30,
            ..ok
        }
        .to_utc()
        .unwrap_err()
        .contains("date"));
        assert!(Civil { month: 13, ..ok }.to_utc().is_err());
        assert!(Civil { hour: 24, ..ok }
            .to_utc()
            .unwrap_err()
            .contains("time"));
        assert!(Civil { year: 1969, ..ok }
            .to_utc()
            .unwrap_err()
            .contains("1970"));
        assert_eq!(days_in_month(2100, 2), 28);
        assert_eq!(days_in_month(2000, 2), 29);
    }
}
